// PoseTrack: the head-pose seam between a producer thread and the render thread.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <thread>

#include "foveal/core/pose_track.hpp"

namespace foveal {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

TimedPose yaw_at(TimeNs t, float deg, float x = 0.0f) {
  return {t, {{x, 1.5f, 0.0f}, glm::angleAxis(deg * kPi / 180.0f, glm::vec3(0, 1, 0))}};
}

float yaw_deg(const Pose& p) {
  const glm::vec3 fwd = p.orientation * glm::vec3(0, 0, -1);
  return std::atan2(-fwd.x, -fwd.z) * 180.0f / kPi;  // positive: turned left
}

TEST(PoseTrack, EmptyHasNoPose) {
  PoseTrack track;
  const PoseAt r = track.pose_at(123);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.pose, Pose{});
  EXPECT_EQ(r.relative, Pose{});
}

TEST(PoseTrack, InterpolatesBetweenTheBracketingPoses) {
  PoseTrack track;
  ASSERT_TRUE(track.push(yaw_at(1000, 0, 0.0f)));
  ASSERT_TRUE(track.push(yaw_at(2000, 10, 1.0f)));
  ASSERT_TRUE(track.push(yaw_at(3000, 30, 1.0f)));
  const PoseAt mid = track.pose_at(1500);
  ASSERT_TRUE(mid.valid);
  EXPECT_NEAR(yaw_deg(mid.pose), 5.0f, 1e-4f);
  EXPECT_NEAR(mid.pose.position_m.x, 0.5f, 1e-6f);
  EXPECT_NEAR(yaw_deg(track.pose_at(2750).pose), 25.0f, 1e-4f);
  // At a sample's own time: that sample, exactly.
  EXPECT_EQ(track.pose_at(2000).pose, yaw_at(2000, 10, 1.0f).pose);
}

TEST(PoseTrack, HoldsAtBothEnds) {
  PoseTrack track;
  ASSERT_TRUE(track.push(yaw_at(1000, 5)));
  EXPECT_EQ(track.pose_at(0).pose, yaw_at(0, 5).pose);  // one pose: held everywhere
  EXPECT_EQ(track.pose_at(5000).pose, yaw_at(0, 5).pose);
  ASSERT_TRUE(track.push(yaw_at(2000, 15)));
  EXPECT_EQ(track.pose_at(999).pose, yaw_at(0, 5).pose);
  EXPECT_EQ(track.pose_at(1'000'000).pose, yaw_at(0, 15).pose);  // no extrapolation
}

TEST(PoseTrack, RelativeIsSeenFromTheFirstPose) {
  PoseTrack track;
  ASSERT_TRUE(track.push(yaw_at(1000, 20, 0.3f)));
  EXPECT_EQ(track.pose_at(1000).relative, Pose{});  // the first pose: exactly the scene's view
  ASSERT_TRUE(track.push(yaw_at(2000, 35, 0.3f)));
  const PoseAt r = track.pose_at(2000);
  EXPECT_NEAR(yaw_deg(r.relative), 15.0f, 1e-4f);
  EXPECT_NEAR(glm::length(r.relative.position_m), 0.0f, 1e-6f);
  track.reset();
  EXPECT_FALSE(track.pose_at(2000).valid);
  ASSERT_TRUE(track.push(yaw_at(3000, 35)));
  EXPECT_EQ(track.pose_at(3000).relative, Pose{});  // reset() chose a new anchor
}

TEST(PoseTrack, WrapsKeepingTheNewestAndTheFirstAsAnchor) {
  PoseTrack track;
  const std::size_t n = PoseTrack::kCapacity + 44;
  for (std::size_t i = 0; i < n; ++i) ASSERT_TRUE(track.push(yaw_at(static_cast<TimeNs>(i + 1) * 1000, static_cast<float>(i) * 0.1f)));
  // The oldest kept is number 44 (t = 45000): earlier times hold it.
  EXPECT_NEAR(yaw_deg(track.pose_at(1000).pose), 4.4f, 1e-4f);
  EXPECT_NEAR(yaw_deg(track.pose_at(45'500).pose), 4.45f, 1e-4f);
  const TimeNs last = static_cast<TimeNs>(n) * 1000;
  EXPECT_NEAR(yaw_deg(track.pose_at(last - 500).pose), (static_cast<float>(n) - 1.5f) * 0.1f, 1e-3f);
  EXPECT_NEAR(yaw_deg(track.pose_at(last).relative), (static_cast<float>(n) - 1.0f) * 0.1f, 1e-3f);  // anchor: pose 0
  EXPECT_EQ(track.accepted(), n);
}

TEST(PoseTrack, DropsOutOfOrderAndBrokenPoses) {
  PoseTrack track;
  ASSERT_TRUE(track.push(yaw_at(1000, 0)));
  EXPECT_FALSE(track.push(yaw_at(1000, 5)));  // same time
  EXPECT_FALSE(track.push(yaw_at(900, 5)));   // back in time
  TimedPose bad = yaw_at(2000, 0);
  bad.pose.orientation = glm::quat(0.5f, 0, 0, 0);
  EXPECT_FALSE(track.push(bad));
  bad.pose.orientation = glm::quat(1, 0, 0, 0);
  bad.pose.position_m.x = std::nanf("");
  EXPECT_FALSE(track.push(bad));
  EXPECT_EQ(track.dropped(), 4u);
  EXPECT_EQ(track.accepted(), 1u);
  // A slightly off-unit quaternion is accepted and renormalised.
  TimedPose off = yaw_at(3000, 0);
  off.pose.orientation = glm::quat(1.0005f, 0, 0, 0);
  ASSERT_TRUE(track.push(off));
  EXPECT_FLOAT_EQ(glm::length(track.pose_at(3000).pose.orientation), 1.0f);
}

// A producer at full speed and a reader asking all the while: every answer lies between
// two neighbouring pushed poses, position and orientation alike (pose i sits at
// x = i cm and yaws (i mod 60) / 2 degrees), never a torn mix. Run under TSan
// (scripts/test.sh).
TEST(PoseTrack, ConcurrentPushAndSampleNeverTear) {
  PoseTrack track;
  constexpr int kPoses = 20000;
  auto yaw_of = [](int i) { return static_cast<float>(i % 60) * 0.5f; };
  std::atomic<bool> done{false};
  std::thread producer([&] {
    for (int i = 0; i < kPoses; ++i) track.push(yaw_at(static_cast<TimeNs>(i + 1) * 1000, yaw_of(i), static_cast<float>(i) * 0.01f));
    done = true;
  });
  std::uint64_t checked = 0, valid = 0;
  while (!done.load() || valid < 1000) {
    const PoseAt r = track.pose_at(static_cast<TimeNs>(checked * 7 % kPoses + 1) * 1000 + 500);
    ++checked;
    if (!r.valid) continue;
    ++valid;
    const double cm = static_cast<double>(r.pose.position_m.x) / 0.01;
    const int i = std::min(static_cast<int>(cm), kPoses - 2);
    const double u = cm - i;
    const double want = yaw_of(i) + u * (yaw_of(i + 1) - yaw_of(i));
    ASSERT_NEAR(yaw_deg(r.pose), want, 0.1) << "pose " << i << " + " << u;
    ASSERT_NEAR(glm::length(r.pose.orientation), 1.0f, 1e-5f);
  }
  producer.join();
  EXPECT_GT(valid, 0u);
  EXPECT_EQ(track.accepted(), static_cast<std::uint64_t>(kPoses));
}

}  // namespace
}  // namespace foveal

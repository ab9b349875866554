// The replay driver: order, re-based timestamps, speed, window, loop, errors.
#include <gtest/gtest.h>

#include "foveal/core/gaze_log.hpp"
#include "foveal/core/pose_track.hpp"
#include "foveal/drivers/replay_source.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

std::vector<GazeSample> drain(ReplaySource& src, std::size_t max = 1u << 20) {
  std::vector<GazeSample> out;
  while (out.size() < max) {
    ReadResult r = src.next(std::chrono::seconds(1));
    if (r.status != ReadStatus::sample) break;
    out.push_back(r.sample);
  }
  return out;
}

ReplayOptions options(const std::string& path, double speed) {
  ReplayOptions o;
  o.path = path;
  o.speed = speed;
  return o;
}

const std::string& bundled() {
  static const std::string p = test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv");
  return p;
}

TEST(Replay, SpeedZeroDeliversEverySampleWithTheRecordedSpacing) {
  auto log = read_gaze_log(bundled());
  ASSERT_TRUE(log);
  ReplaySource src(options(bundled(), 0.0));
  ASSERT_TRUE(src.open());
  ASSERT_TRUE(src.start());
  const TimeNs before = monotonic_now_ns();
  const auto out = drain(src);
  ASSERT_EQ(out.size(), log->size());
  EXPECT_GE(out[0].t_ns, before);  // re-based onto the runtime clock
  for (std::size_t i = 1; i < out.size(); ++i) {
    EXPECT_EQ(out[i].t_ns - out[i - 1].t_ns, (*log)[i].t_ns - (*log)[i - 1].t_ns) << i;
    EXPECT_EQ(out[i].eyes, (*log)[i].eyes) << i;
  }
  EXPECT_EQ(src.next(std::chrono::milliseconds(1)).status, ReadStatus::end);
  EXPECT_EQ(src.info().driver, "replay");
  EXPECT_DOUBLE_EQ(src.info().nominal_rate_hz, 120.0);
}

// The pose seam end to end: the replay delivers each sample's recorded head pose with
// it, stamped with the sample's runtime-clock time (start + (t - t_first) / speed), and a
// PoseTrack fed from the delivered samples answers with the recorded poses at those times.
TEST(Replay, DeliversTheRecordedHeadPoseOnTheRuntimeClock) {
  auto log = read_gaze_log(bundled());
  ASSERT_TRUE(log);
  ReplayOptions o = options(bundled(), 20.0);
  o.end_s = 1.0;
  ReplaySource src(o);
  ASSERT_TRUE(src.open());
  ASSERT_TRUE(src.start());
  EXPECT_TRUE(src.info().head_pose);
  const auto out = drain(src);
  ASSERT_GT(out.size(), 100u);
  PoseTrack track;
  for (const GazeSample& s : out) {
    ASSERT_TRUE(s.head.valid);
    ASSERT_TRUE(track.push({s.t_ns, s.head.pose}));
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_EQ(out[i].head, (*log)[i].head) << i;
    EXPECT_EQ(track.pose_at(out[i].t_ns).pose, (*log)[i].head.pose) << i;
  }
  EXPECT_EQ(track.pose_at(out[0].t_ns).relative, Pose{});
  EXPECT_NE(track.pose_at(out.back().t_ns).relative, Pose{});  // the head moved

  ReplaySource v1(options(test::source_path("tests/vm/data/constant_gaze.csv"), 0.0));
  ASSERT_TRUE(v1.open());
  EXPECT_FALSE(v1.info().head_pose);
}

TEST(Replay, SpeedScalesTheTimeline) {
  auto log = read_gaze_log(bundled());
  ASSERT_TRUE(log);
  ReplayOptions o = options(bundled(), 20.0);
  o.end_s = 0.5;  // 60 samples in 25 ms
  ReplaySource src(o);
  ASSERT_TRUE(src.open());
  ASSERT_TRUE(src.start());
  const auto out = drain(src);
  ASSERT_GT(out.size(), 50u);
  for (std::size_t i = 1; i < out.size(); ++i) {
    const double recorded = static_cast<double>((*log)[i].t_ns - (*log)[0].t_ns) / 20.0;
    EXPECT_NEAR(static_cast<double>(out[i].t_ns - out[0].t_ns), recorded, 1.0) << i;
  }
}

TEST(Replay, WindowSelectsTheRightSamples) {
  auto log = read_gaze_log(bundled());
  ASSERT_TRUE(log);
  ReplayOptions o = options(bundled(), 0.0);
  o.start_s = 2.0;
  o.end_s = 3.0;
  ReplaySource src(o);
  ASSERT_TRUE(src.open());
  ASSERT_TRUE(src.start());
  const auto out = drain(src);
  std::vector<GazeSample> expected;
  for (const auto& s : *log) {
    const double t = static_cast<double>(s.t_ns - (*log)[0].t_ns) / 1e9;
    if (t >= 2.0 && t <= 3.0) expected.push_back(s);
  }
  ASSERT_EQ(out.size(), expected.size());
  EXPECT_EQ(out.front().eyes, expected.front().eyes);
  EXPECT_EQ(out.back().eyes, expected.back().eyes);
}

TEST(Replay, LoopKeepsTimestampsIncreasing) {
  ReplayOptions o = options(bundled(), 0.0);
  o.loop = true;
  o.end_s = 1.0;
  ReplaySource src(o);
  ASSERT_TRUE(src.open());
  ASSERT_TRUE(src.start());
  const auto out = drain(src, 700);  // ~5.8 passes of ~120 samples
  ASSERT_EQ(out.size(), 700u);
  for (std::size_t i = 1; i < out.size(); ++i) ASSERT_GT(out[i].t_ns, out[i - 1].t_ns) << i;
  EXPECT_GE(src.loops_completed(), 5u);
}

TEST(Replay, ErrorsAreValues) {
  test::TempDir dir;
  ReplaySource missing(options(dir.path("nope.csv"), 1.0));
  auto s = missing.open();
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("nope.csv"), std::string::npos);
  ReplaySource not_started(options(bundled(), 1.0));
  ASSERT_TRUE(not_started.open());
  EXPECT_EQ(not_started.next(std::chrono::milliseconds(1)).status, ReadStatus::error);
  ReplayOptions bad = options(bundled(), -1.0);
  EXPECT_FALSE(ReplaySource(bad).open());
  ReplayOptions empty_window = options(bundled(), 0.0);
  empty_window.start_s = 100.0;
  ReplaySource e(empty_window);
  ASSERT_TRUE(e.open());
  EXPECT_FALSE(e.start());
}

}  // namespace
}  // namespace foveal

// The pose thread on a scripted PoseDevice: fused IMU orientation reaches the track,
// prediction carries it forward, an unplug holds the last pose and says so, a replug
// recovers.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <thread>

#include "foveal/runtime/head_tracker.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

/// A 1 kHz IMU turning at 0.5 rad/s about the head's up axis, level; it can be
/// "unplugged" (next() says disconnected, open() fails) and plugged back.
class ScriptedImu final : public PoseDevice {
 public:
  std::atomic<bool> plugged{true};
  std::atomic<int> opens{0};
  Status open() override {
    if (!plugged) return Error{ErrorKind::device, "scripted: unplugged"};
    ++opens;
    return {};
  }
  void close() override {}
  Status start() override { return {}; }
  void stop() override {}
  PoseReading next(std::chrono::nanoseconds) override {
    PoseReading r;
    if (!plugged) {
      r.status = ReadStatus::disconnected;
      r.error = {ErrorKind::device, "scripted: gone"};
      return r;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    r.status = ReadStatus::sample;
    r.has_imu = true;
    r.imu.t_ns = monotonic_now_ns();
    r.imu.gyro_rad_s = {0.0f, 0.5f, 0.0f};
    r.imu.accel_m_s2 = {0.0f, kGravity, 0.0f};
    return r;
  }
  PoseDeviceInfo info() const override {
    PoseDeviceInfo i;
    i.driver = "scripted";
    i.imu = true;
    return i;
  }
};

TEST(HeadTracker, FusesPredictsHoldsAndRecovers) {
  ScriptedImu imu;
  HeadTracker t(imu);
  t.start();
  ASSERT_TRUE(test::eventually([&] { return t.stats().poses > 200; }));
  EXPECT_EQ(t.stats().state, HeadState::tracking);
  // Yaw grows at 0.5 rad/s: a prediction 50 ms ahead turns ~1.4° further than the newest pose.
  const TimedPose newest = *t.track().newest();
  const PoseAt ahead = t.predicted(newest.t_ns + 50 * kNsPerMs);
  ASSERT_TRUE(ahead.valid);
  EXPECT_NEAR(angle_between(ahead.pose.orientation, newest.pose.orientation), 0.025, 0.004);

  imu.plugged = false;
  ASSERT_TRUE(test::eventually([&] { return t.stats().state == HeadState::reconnecting; }));
  const TimedPose held = *t.track().newest();
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  EXPECT_TRUE(t.stats().state == HeadState::reconnecting);
  // The last pose is held: the track answers with it, prediction does not extrapolate.
  const PoseAt later = t.predicted(monotonic_now_ns() + 20 * kNsPerMs);
  ASSERT_TRUE(later.valid);
  EXPECT_NEAR(angle_between(later.pose.orientation, held.pose.orientation), 0.0, 1e-6);
  EXPECT_EQ(t.track().pose_at(monotonic_now_ns()).pose, held.pose);

  imu.plugged = true;
  ASSERT_TRUE(test::eventually([&] { return t.stats().reconnects == 1 && t.stats().state == HeadState::tracking; }));
  EXPECT_GE(t.stats().disconnects, 1u);
  ASSERT_TRUE(test::eventually([&] { return t.track().newest()->t_ns > held.t_ns; }));
  t.stop();
  EXPECT_EQ(t.stats().state, HeadState::stopped);
}

/// A 6DoF device moving along x at 1 m/s: poses 10 ms apart on its own clock, read in
/// bursts whose runtime times are 1 µs apart (as after a delivery stall).
class ScriptedSlam final : public PoseDevice {
 public:
  int k = 0;
  Status open() override { return {}; }
  void close() override {}
  Status start() override { return {}; }
  void stop() override {}
  PoseReading next(std::chrono::nanoseconds) override {
    PoseReading r;
    if (k >= 40) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      return r;  // timeout
    }
    r.status = ReadStatus::sample;
    r.has_pose = true;
    r.pose.t_ns = kNsPerSec + (k / 8) * 80 * kNsPerMs + (k % 8) * 1000;
    r.pose.pose.position_m = {0.01f * static_cast<float>(k), 1.6f, 0.0f};
    r.pose_has_device_time = true;
    r.pose_device_t_ns = 7 * kNsPerSec + k * 10 * kNsPerMs;
    ++k;
    return r;
  }
  PoseDeviceInfo info() const override {
    PoseDeviceInfo i;
    i.driver = "scripted";
    i.position = i.orientation = true;
    return i;
  }
};

TEST(HeadTracker, VelocityIsOverTheDevicesClock) {
  ScriptedSlam slam;
  HeadTracker t(slam, /*wait_for_device=*/false);
  t.start();
  ASSERT_TRUE(test::eventually([&] { return t.stats().poses == 40; }));
  t.stop();
  const MotionEstimate m = t.motion();
  EXPECT_NEAR(m.velocity_m_s.x, 1.0f, 1e-3f);  // on the runtime times it would be ~10000 m/s
  EXPECT_NEAR(m.velocity_m_s.y, 0.0f, 1e-6f);
}

TEST(HeadTracker, WaitsForAnAbsentDevice) {
  ScriptedImu imu;
  imu.plugged = false;
  HeadTracker t(imu);
  t.start();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(t.stats().state, HeadState::waiting);
  EXPECT_FALSE(t.predicted(monotonic_now_ns()).valid);
  imu.plugged = true;
  ASSERT_TRUE(test::eventually([&] { return t.stats().state == HeadState::tracking; }));
  t.stop();
}

TEST(PosePrediction, ConstantVelocityAndItsError) {
  MotionEstimate m;
  m.valid = true;
  m.pose = {kNsPerSec, Pose{}};
  m.angular_velocity = {0.0f, 1.0f, 0.0f};
  m.velocity_m_s = {0.5f, 0.0f, 0.0f};
  const Pose p = predict_pose(m, kNsPerSec + 20 * kNsPerMs);
  EXPECT_NEAR(angle_between(p.orientation, Pose{}.orientation), 0.02, 1e-5);
  EXPECT_NEAR(p.position_m.x, 0.01f, 1e-6f);
  // Capped horizon, and never backwards.
  EXPECT_NEAR(angle_between(predict_pose(m, 10 * kNsPerSec).orientation, Pose{}.orientation), 0.1, 1e-5);
  EXPECT_EQ(predict_pose(m, 0), m.pose.pose);

  // The track turns at exactly that rate: predictions score ~0, holding the pose does not.
  PoseTrack track;
  PredictionErrors e;
  for (int i = 0; i <= 100; ++i) {
    const TimeNs t = kNsPerSec + i * 10 * kNsPerMs;
    const Pose at{glm::vec3(0.0f), glm::angleAxis(static_cast<float>(i) * 0.01f, glm::vec3(0, 1, 0))};
    track.push({t, at});
    if (i < 99) {
      MotionEstimate mm = m;
      mm.pose = {t, at};
      mm.velocity_m_s = glm::vec3(0.0f);
      e.add(t + 20 * kNsPerMs, predict_pose(mm, t + 20 * kNsPerMs), at);
    }
  }
  e.resolve(track);
  EXPECT_EQ(e.angle_deg().count, 99u);
  EXPECT_LT(e.angle_deg().max, 0.01);
  EXPECT_NEAR(e.held_angle_deg().p50, 0.02 * 180 / 3.14159265, 0.01);
  EXPECT_EQ(e.pending(), 0u);
}

}  // namespace
}  // namespace foveal

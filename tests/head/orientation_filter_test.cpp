// The 3DoF filter on a synthetic head rotation with a gyro bias and noise on both
// sensors: it recovers the orientation within the error docs/headset.md states.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "foveal/runtime/orientation_filter.hpp"
#include "foveal/runtime/pose_prediction.hpp"

namespace foveal {
namespace {

constexpr double kDeg = 180.0 / 3.14159265358979323846;

/// The true head orientation: still for the first `rest_s`, then yaw, pitch and roll
/// oscillating (up to ±46°, ±23°, ±17°; peak rates about 25 °/s), still again in
/// [rest2_from, rest2_to).
struct Motion {
  double rest_s = 3, rest2_from = 23, rest2_to = 25;
  double moving(double t) const {
    if (t < rest_s) return 0;
    if (t >= rest2_from && t < rest2_to) return rest2_from - rest_s;
    return t >= rest2_to ? t - rest_s - (rest2_to - rest2_from) : t - rest_s;
  }
  glm::quat at(double t) const {
    const double u = moving(t);
    const float yaw = static_cast<float>(0.8 * std::sin(0.5 * u));
    const float pitch = static_cast<float>(0.4 * std::sin(0.7 * u));
    const float roll = static_cast<float>(0.3 * std::sin(0.9 * u));
    return glm::angleAxis(yaw, glm::vec3(0, 1, 0)) * glm::angleAxis(pitch, glm::vec3(1, 0, 0)) *
           glm::angleAxis(roll, glm::vec3(0, 0, 1));
  }
};

struct FilterRun {
  double max_tilt_deg = 0, rms_deg = 0, final_deg = 0;
  /// One 90 Hz refresh ahead: the fused pose predicted with the gyro, and held, against
  /// the fused pose then (RMS, degrees).
  double predicted_rms_deg = 0, held_rms_deg = 0;
  glm::vec3 bias{0.0f};
};

FilterRun simulate(OrientationFilterParams params, double seconds = 45) {
  const Motion m;
  const glm::vec3 bias(0.01f, -0.015f, 0.02f);  // rad/s: 0.6-1.1 °/s, a typical MEMS offset
  std::mt19937 rng(7);
  std::normal_distribution<float> gyro_noise(0.0f, 0.005f), accel_noise(0.0f, 0.05f);
  OrientationFilter f(params);
  const double dt = 1e-3;  // a 1 kHz IMU
  FilterRun run;
  double sum2 = 0, pred2 = 0, held2 = 0;
  std::size_t n = 0, np = 0;
  constexpr int kAhead = 11;  // samples: 11 ms, one 90 Hz refresh
  std::vector<glm::quat> predicted(static_cast<std::size_t>(seconds / dt) + 2), held(predicted.size());
  for (int i = 0; i * dt < seconds; ++i) {
    const double t = i * dt;
    const glm::quat q0 = m.at(t), q1 = m.at(t + dt);
    // Body rates from the true motion: q1 = q0 ⊗ exp(ω dt).
    glm::quat d = glm::normalize(glm::inverse(q0) * q1);
    if (d.w < 0) d = -d;
    const glm::vec3 v(d.x, d.y, d.z);
    const float sin_half = glm::length(v);  // atan2, not acos: the steps are tiny
    const glm::vec3 omega =
        sin_half > 0 ? v / sin_half * (2.0f * std::atan2(sin_half, d.w) / static_cast<float>(dt)) : glm::vec3(0.0f);
    ImuSample s;
    s.t_ns = static_cast<TimeNs>(t * 1e9);
    s.gyro_rad_s = omega + bias + glm::vec3(gyro_noise(rng), gyro_noise(rng), gyro_noise(rng));
    s.accel_m_s2 = glm::inverse(q0) * glm::vec3(0, kGravity, 0) +
                   glm::vec3(accel_noise(rng), accel_noise(rng), accel_noise(rng));
    f.update(s);
    const auto k = static_cast<std::size_t>(i);
    MotionEstimate me;
    me.valid = true;
    me.pose = {s.t_ns, Pose{glm::vec3(0.0f), f.orientation()}};
    me.angular_velocity = f.angular_velocity();
    predicted[k] = predict_pose(me, s.t_ns + kAhead * kNsPerMs).orientation;
    held[k] = f.orientation();
    if (t >= 1.0 && k >= kAhead) {
      const double ep = angle_between(predicted[k - kAhead], f.orientation()) * kDeg;
      const double eh = angle_between(held[k - kAhead], f.orientation()) * kDeg;
      pred2 += ep * ep, held2 += eh * eh, ++np;
    }
    if (t < 1.0) continue;  // the first second: settling
    const glm::quat est = f.orientation();
    const glm::vec3 up_true = glm::inverse(q0) * glm::vec3(0, 1, 0), up_est = glm::inverse(est) * glm::vec3(0, 1, 0);
    const double tilt = std::acos(std::min(1.0f, glm::dot(up_true, up_est))) * kDeg;
    run.max_tilt_deg = std::max(run.max_tilt_deg, tilt);
    const double e = angle_between(est, q0) * kDeg;
    sum2 += e * e;
    ++n;
    run.final_deg = e;
  }
  run.rms_deg = std::sqrt(sum2 / static_cast<double>(n));
  run.predicted_rms_deg = std::sqrt(pred2 / static_cast<double>(np));
  run.held_rms_deg = std::sqrt(held2 / static_cast<double>(np));
  run.bias = f.gyro_bias() - bias;
  return run;
}

TEST(OrientationFilter, RecoversARotationWithGyroBiasAndNoise) {
  const FilterRun r = simulate({});
  std::printf("tilt max %.2f deg, orientation rms %.2f deg, final %.2f deg, bias error %.4f rad/s\n", r.max_tilt_deg,
              r.rms_deg, r.final_deg, double(glm::length(r.bias)));
  // The stated error (docs/headset.md): tilt within 0.5°, the whole orientation (yaw
  // drifts with the residual bias) within 1° RMS and 1.5° after 45 s (measured: 0.10°,
  // 0.32°, 0.40°).
  EXPECT_LT(r.max_tilt_deg, 0.5);
  EXPECT_LT(r.rms_deg, 1.0);
  EXPECT_LT(r.final_deg, 1.5);
  EXPECT_LT(glm::length(r.bias), 0.001f);
}

TEST(OrientationFilter, PredictionOneRefreshAheadBeatsHoldingThePose) {
  const FilterRun r = simulate({});
  std::printf("11 ms ahead: predicted %.3f deg rms, held %.3f deg rms\n", r.predicted_rms_deg, r.held_rms_deg);
  EXPECT_LT(r.predicted_rms_deg, 0.25 * r.held_rms_deg);
}

TEST(OrientationFilter, WithoutBiasEstimationYawDrifts) {
  OrientationFilterParams p;
  p.estimate_bias = false;
  const FilterRun r = simulate(p);
  // 0.02 rad/s about the head's up axis over 44 s is about 50°: the test above can fail.
  EXPECT_GT(r.final_deg, 10.0);
  EXPECT_LT(r.max_tilt_deg, 5.0);  // the accelerometer still holds the tilt
}

TEST(OrientationFilter, StartsLevelFromTheAccelerometer) {
  OrientationFilter f;
  ImuSample s;
  s.accel_m_s2 = glm::angleAxis(0.3f, glm::vec3(1, 0, 0)) * glm::vec3(0, kGravity, 0);  // "up" tilted in the head
  f.update(s);
  ASSERT_TRUE(f.initialised());
  const glm::vec3 up_world = f.orientation() * glm::normalize(s.accel_m_s2);
  EXPECT_NEAR(up_world.y, 1.0f, 1e-5f);
}

TEST(OrientationFilter, IntegratesOverTheDeviceClockWhenArrivalsBunch) {
  // 1 s at 0.5 rad/s about up. The runtime times of the second half bunch 1 ns apart
  // (the driver's clock mapping holding them back after a late burst), the device's stay
  // 1 ms apart: on the runtime times the filter would turn half as far.
  OrientationFilterParams p;
  p.estimate_bias = false;
  OrientationFilter f(p);
  for (int i = 0; i <= 1000; ++i) {
    ImuSample s;
    s.t_ns = std::min(i, 500) * kNsPerMs + std::max(0, i - 500);
    s.has_device_time = true;
    s.device_t_ns = 5 * kNsPerSec + i * kNsPerMs;
    s.gyro_rad_s = {0.0f, 0.5f, 0.0f};
    s.accel_m_s2 = {0.0f, kGravity, 0.0f};
    f.update(s);
  }
  EXPECT_NEAR(angle_between(f.orientation(), glm::quat(1, 0, 0, 0)), 0.5, 1e-3);
}

TEST(OrientationFilter, IgnoresOldSamplesAndGaps) {
  OrientationFilter f;
  ImuSample s;
  s.accel_m_s2 = {0, kGravity, 0};
  s.t_ns = kNsPerSec;
  f.update(s);
  s.gyro_rad_s = {0, 1.0f, 0};
  s.t_ns = kNsPerSec - 1;  // older: ignored
  f.update(s);
  EXPECT_NEAR(angle_between(f.orientation(), glm::quat(1, 0, 0, 0)), 0.0, 1e-6);
  s.t_ns = 2 * kNsPerSec;  // a 1 s gap: not integrated
  f.update(s);
  EXPECT_NEAR(angle_between(f.orientation(), glm::quat(1, 0, 0, 0)), 0.0, 1e-6);
}

}  // namespace
}  // namespace foveal

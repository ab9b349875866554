#pragma once
// The head motion the emulated headsets report (vm_psvr2.cpp, vm_vive.cpp), as a
// function of the guest's CLOCK_MONOTONIC time, so the checker (vm_hmd.cpp) can say
// where the head was at any time foveald names. On the runtime's axes (x right, y up,
// -z forward, docs/conventions.md), the tracking frame's y axis up.
#include <cmath>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "foveal/core/clock.hpp"
#include "foveal/core/imu_sample.hpp"

namespace foveal::vmtest {

struct HeadMotion {
  glm::dvec3 position_m{0.0};
  glm::dquat orientation{1, 0, 0, 0};
  glm::dvec3 angular_velocity_head{0.0};  ///< rad/s, in the head frame (what a gyroscope reads)
  glm::dvec3 specific_force_head{0.0};    ///< m/s^2, in the head frame (what an accelerometer reads)
};

inline double seconds(TimeNs t) { return static_cast<double>(t) * 1e-9; }

/// The head turning at a constant rate about the vertical, pitched by a constant angle,
/// while it moves along `position(t)` with acceleration `accel(t)`.
template <class Position, class Accel>
HeadMotion yaw_motion(double t, double yaw_rate, double pitch, Position position, Accel accel) {
  HeadMotion m;
  const glm::dquat yaw = glm::angleAxis(yaw_rate * t, glm::dvec3(0, 1, 0));
  m.orientation = yaw * glm::angleAxis(pitch, glm::dvec3(1, 0, 0));
  m.position_m = position(t);
  const glm::dquat to_head = glm::conjugate(m.orientation);
  m.angular_velocity_head = to_head * glm::dvec3(0, yaw_rate, 0);
  m.specific_force_head = to_head * (accel(t) + glm::dvec3(0, double(kGravity), 0));
  return m;
}

/// PS VR2 (6DoF from its SLAM): a constant-rate yaw and a translation on an ellipse,
/// bobbing up and down.
constexpr double kPsvr2YawRate = 0.5;  // rad/s
inline HeadMotion psvr2_motion(TimeNs t_ns) {
  constexpr double a = 0.6, b = 1.3;  // rad/s of the circle and the bob
  return yaw_motion(
      seconds(t_ns), kPsvr2YawRate, 0.0,
      [](double t) { return glm::dvec3(0.20 * std::sin(a * t), 1.60 + 0.05 * std::sin(b * t), 0.15 * std::cos(a * t) - 0.30); },
      [](double t) {
        return glm::dvec3(-0.20 * a * a * std::sin(a * t), -0.05 * b * b * std::sin(b * t), -0.15 * a * a * std::cos(a * t));
      });
}

/// Vive-class (3DoF from its IMU): a constant-rate yaw with the head pitched down; no
/// translation (an IMU-only headset has no position).
constexpr double kViveYawRate = 0.6, kVivePitch = -0.2;  // rad/s, rad
inline HeadMotion vive_motion(TimeNs t_ns) {
  return yaw_motion(
      seconds(t_ns), kViveYawRate, kVivePitch, [](double) { return glm::dvec3(0.0); },
      [](double) { return glm::dvec3(0.0); });
}

}  // namespace foveal::vmtest

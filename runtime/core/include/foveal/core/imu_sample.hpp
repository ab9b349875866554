#pragma once
// One inertial measurement on the runtime's head axes (x right, y up, -z forward;
// docs/conventions.md), as an HMD driver delivers it after scaling and calibration.
#include <cstdint>

#include <glm/vec3.hpp>

#include "foveal/core/clock.hpp"

namespace foveal {

struct ImuSample {
  TimeNs t_ns = 0;             ///< runtime clock (CLOCK_MONOTONIC ns)
  glm::vec3 gyro_rad_s{0.0f};  ///< angular velocity of the head frame, in the head frame
  /// Specific force in the head frame: at rest it points up (+9.81 m/s² along the
  /// head's "up" when the head is level), the way accelerometers read gravity.
  glm::vec3 accel_m_s2{0.0f};
  /// The device's own timestamp (unwrapped, ns), when it has one: what the gyro is
  /// integrated over. t_ns is re-anchored to arrivals and may bunch samples together.
  bool has_device_time = false;
  std::int64_t device_t_ns = 0;
};

/// Standard gravity, m/s².
constexpr float kGravity = 9.80665f;

}  // namespace foveal

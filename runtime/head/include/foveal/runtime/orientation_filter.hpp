#pragma once
// 3DoF orientation from an IMU alone (headsets without their own tracking: the Vive
// here): a complementary filter in the form of Mahony et al. (2008), with the gyro
// bias estimated while the head is at rest. docs/headset.md states the method and its
// parameters.
//
//   q ← q ⊗ exp(½ (ω − b + k_p e) dt),  e = â × (q⁻¹ · up)
//
// ω the gyro, b the bias estimate, â the accelerometer's unit vector (it reads "up" at
// rest), up = +y. The tilt correction e only acts while |‖a‖ − g| is small (the head is
// not accelerating much); yaw is not observable without a reference and drifts with
// the residual bias. At rest (gyro and accelerometer quiet for rest_hold_s), b is the
// mean of ω over all rest so far, then follows ω with time constant bias_tau_s.
#include <optional>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "foveal/core/imu_sample.hpp"

namespace foveal {

struct OrientationFilterParams {
  float tilt_gain = 1.0f;          ///< k_p, 1/s: tilt errors decay with time constant 1/k_p
  float accel_gate = 0.1f;         ///< tilt correction only while |‖a‖ − g| < accel_gate·g
  float rest_gyro_rad_s = 0.05f;   ///< at rest: |ω − b| below this (2.9 °/s) ...
  float rest_accel = 0.05f;        ///< ... and |‖a‖ − g| < rest_accel·g ...
  float rest_hold_s = 0.25f;       ///< ... for this long
  float bias_tau_s = 1.0f;         ///< bias low-pass time constant while at rest
  bool estimate_bias = true;
  float max_dt_s = 0.05f;          ///< longer gaps (a lost device) are not integrated
};

/// Not thread-safe: one filter per IMU stream, fed from one thread.
class OrientationFilter {
 public:
  explicit OrientationFilter(OrientationFilterParams p = {}) : p_(p) {}

  /// Adds one sample (times strictly increasing; an older or equal one is ignored). The
  /// gyro is integrated over the device's own clock when the samples carry it.
  /// The first sample sets the tilt from the accelerometer (yaw 0).
  void update(const ImuSample& s);

  bool initialised() const { return initialised_; }
  /// Head frame -> world frame (y up), unit.
  const glm::quat& orientation() const { return q_; }
  const glm::vec3& gyro_bias() const { return bias_; }
  /// The last gyro reading with the bias removed: the head's angular velocity.
  const glm::vec3& angular_velocity() const { return omega_; }
  bool at_rest() const { return rest_for_s_ >= p_.rest_hold_s; }
  TimeNs last_t_ns() const { return last_t_; }
  /// Forgets the orientation (a new device) but keeps the bias estimate.
  void reset();

 private:
  OrientationFilterParams p_;
  bool initialised_ = false;
  glm::quat q_{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec3 bias_{0.0f}, omega_{0.0f};
  float rest_for_s_ = 0, rest_total_s_ = 0;
  TimeNs last_t_ = 0;
  std::optional<std::int64_t> last_device_t_;
};

/// exp of a rotation vector (axis · angle) as a unit quaternion.
glm::quat rotation_vector_to_quat(const glm::vec3& v);
/// The rotation angle between two orientations, radians in [0, π].
double angle_between(const glm::quat& a, const glm::quat& b);

}  // namespace foveal

#include "foveal/runtime/orientation_filter.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace foveal {

glm::quat rotation_vector_to_quat(const glm::vec3& v) {
  const float angle = glm::length(v);
  if (angle < 1e-9f) return glm::normalize(glm::quat(1.0f, 0.5f * v.x, 0.5f * v.y, 0.5f * v.z));
  const float s = std::sin(0.5f * angle) / angle;
  return {std::cos(0.5f * angle), v.x * s, v.y * s, v.z * s};
}

double angle_between(const glm::quat& a, const glm::quat& b) {
  // From the vector part of a⁻¹b, in double: acos of the dot product loses the digits of
  // small angles.
  const glm::dquat d = glm::conjugate(glm::dquat(a.w, a.x, a.y, a.z)) * glm::dquat(b.w, b.x, b.y, b.z);
  const double s = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  return 2.0 * std::atan2(s, std::fabs(d.w));
}

namespace {

/// The rotation taking unit vector `from` onto unit vector `to` (shortest arc).
glm::quat from_to(const glm::vec3& from, const glm::vec3& to) {
  const float c = glm::dot(from, to);
  if (c < -0.999999f) return glm::quat(0.0f, 1.0f, 0.0f, 0.0f);  // upside down: any axis ⟂ y
  const glm::vec3 axis = glm::cross(from, to);
  return glm::normalize(glm::quat(1.0f + c, axis.x, axis.y, axis.z));
}

}  // namespace

void OrientationFilter::reset() {
  initialised_ = false;
  last_device_t_.reset();
  q_ = glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  omega_ = glm::vec3(0.0f);
  rest_for_s_ = 0;
}

void OrientationFilter::update(const ImuSample& s) {
  const float a_norm = glm::length(s.accel_m_s2);
  if (!initialised_) {
    // Tilt from gravity: q maps head -> world, so it takes the measured "up" onto +y.
    if (a_norm > 0.5f * kGravity) q_ = from_to(s.accel_m_s2 / a_norm, glm::vec3(0, 1, 0));
    initialised_ = true;
    last_t_ = s.t_ns;
    last_device_t_ = s.has_device_time ? std::optional<std::int64_t>(s.device_t_ns) : std::nullopt;
    omega_ = s.gyro_rad_s - bias_;
    return;
  }
  if (s.t_ns <= last_t_) return;
  // The step on the device's clock when both samples have one (the runtime times are
  // re-anchored to arrivals and may bunch a burst together), else on the runtime's.
  const std::int64_t step_ns = s.has_device_time && last_device_t_ ? s.device_t_ns - *last_device_t_ : s.t_ns - last_t_;
  const float dt = static_cast<float>(step_ns) * 1e-9f;
  last_t_ = s.t_ns;
  last_device_t_ = s.has_device_time ? std::optional<std::int64_t>(s.device_t_ns) : std::nullopt;
  omega_ = s.gyro_rad_s - bias_;
  if (!(dt > 0) || dt > p_.max_dt_s) {  // a gap, or a device clock that restarted: nothing to integrate
    rest_for_s_ = 0;
    return;
  }
  const float accel_error = std::fabs(a_norm - kGravity) / kGravity;

  // At rest: the gyro reads only its bias (plus noise).
  if (glm::length(omega_) < p_.rest_gyro_rad_s && accel_error < p_.rest_accel) rest_for_s_ += dt;
  else rest_for_s_ = 0;
  if (p_.estimate_bias && at_rest()) {
    // A running mean over all the rest seen so far, then a low-pass with bias_tau_s:
    // the first rest already gives the full estimate.
    rest_total_s_ += dt;
    bias_ += (s.gyro_rad_s - bias_) * (dt / std::min(p_.bias_tau_s, rest_total_s_));
    omega_ = s.gyro_rad_s - bias_;
  }

  glm::vec3 w = omega_;
  if (a_norm > 0 && accel_error < p_.accel_gate) {
    const glm::vec3 up_measured = s.accel_m_s2 / a_norm;
    const glm::vec3 up_estimated = glm::inverse(q_) * glm::vec3(0, 1, 0);
    w += p_.tilt_gain * glm::cross(up_measured, up_estimated);
  }
  q_ = glm::normalize(q_ * rotation_vector_to_quat(w * dt));
}

}  // namespace foveal

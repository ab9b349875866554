#include "foveal/core/pose.hpp"

#include <cmath>

namespace foveal {

bool is_finite(const Pose& p) {
  const glm::quat& q = p.orientation;
  return std::isfinite(p.position_m.x) && std::isfinite(p.position_m.y) && std::isfinite(p.position_m.z) &&
         std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z);
}

double quaternion_norm(const glm::quat& q) {
  return std::sqrt(double{q.w} * q.w + double{q.x} * q.x + double{q.y} * q.y + double{q.z} * q.z);
}

bool is_unit(const glm::quat& q) {
  if (!std::isfinite(q.w) || !std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) return false;
  return std::abs(quaternion_norm(q) - 1.0) <= kUnitQuaternionTolerance;
}

glm::quat renormalized(const glm::quat& q) {
  const double n = quaternion_norm(q);
  if (std::abs(n - 1.0) <= 2.5e-7) return q;  // within ~2 float ulps of 1
  const float inv = static_cast<float>(1.0 / n);
  return glm::quat(q.w * inv, q.x * inv, q.y * inv, q.z * inv);
}

Pose compose(const Pose& a, const Pose& b) {
  Pose r;
  r.orientation = a.orientation * b.orientation;
  r.position_m = a.orientation * b.position_m + a.position_m;
  return r;
}

Pose inverse(const Pose& p) {
  Pose r;
  r.orientation = glm::conjugate(p.orientation);
  r.position_m = r.orientation * -p.position_m;
  return r;
}

Pose relative_to(const Pose& anchor, const Pose& p) {
  if (p == anchor) return Pose{};
  Pose r = compose(inverse(anchor), p);
  r.orientation = renormalized(r.orientation);
  return r;
}

Pose interpolate(const Pose& a, const Pose& b, double u) {
  if (!(u > 0.0)) return a;  // NaN holds the earlier pose too
  if (u >= 1.0) return b;
  // In double: the two samples of a 120 Hz track are close, where float slerp loses
  // digits to the small angle.
  const glm::dquat qa(a.orientation), qb(b.orientation);
  glm::dquat q = glm::slerp(qa, qb, u);  // takes the shorter arc
  Pose r;
  r.orientation = glm::quat(glm::normalize(q));
  r.position_m = glm::vec3(glm::mix(glm::dvec3(a.position_m), glm::dvec3(b.position_m), u));
  return r;
}

}  // namespace foveal

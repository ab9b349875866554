#pragma once
// Rigid poses for the layer: composition, inverse, and the orientation that turns
// OpenXR's forward (-z) onto a gaze direction. Plain arithmetic on XrPosef.
#include <openxr/openxr.h>

#include <cmath>

namespace foveal::openxr {

inline XrQuaternionf quat_mul(const XrQuaternionf& a, const XrQuaternionf& b) {
  return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
          a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}

inline XrVector3f rotate(const XrQuaternionf& q, const XrVector3f& v) {
  // v + 2w(u x v) + 2 u x (u x v), u the quaternion's vector part.
  const XrVector3f u{q.x, q.y, q.z};
  const XrVector3f t{2 * (u.y * v.z - u.z * v.y), 2 * (u.z * v.x - u.x * v.z), 2 * (u.x * v.y - u.y * v.x)};
  return {v.x + q.w * t.x + (u.y * t.z - u.z * t.y), v.y + q.w * t.y + (u.z * t.x - u.x * t.z),
          v.z + q.w * t.z + (u.x * t.y - u.y * t.x)};
}

/// a ∘ b: b expressed in a's frame, then a's frame in its parent.
inline XrPosef compose(const XrPosef& a, const XrPosef& b) {
  const XrVector3f p = rotate(a.orientation, b.position);
  return {quat_mul(a.orientation, b.orientation), {a.position.x + p.x, a.position.y + p.y, a.position.z + p.z}};
}

inline XrPosef inverse(const XrPosef& a) {
  const XrQuaternionf qi{-a.orientation.x, -a.orientation.y, -a.orientation.z, a.orientation.w};
  const XrVector3f p = rotate(qi, a.position);
  return {qi, {-p.x, -p.y, -p.z}};
}

inline XrPosef identity_pose() { return {{0, 0, 0, 1}, {0, 0, 0}}; }

/// The shortest rotation taking (0,0,-1) onto the unit direction d. No roll: the gaze
/// pose's up stays as close to the head's up as the turn allows.
inline XrQuaternionf look_rotation(const XrVector3f& d) {
  // q = (f x d, 1 + f·d) normalised, with f = (0,0,-1): f x d = (d.y, -d.x, 0).
  const float w = 1.0f - d.z;
  if (w < 1e-6f) return {0, 1, 0, 0};  // straight back: any half turn about y
  const float n = std::sqrt(d.y * d.y + d.x * d.x + w * w);
  return {d.y / n, -d.x / n, 0.0f, w / n};
}

}  // namespace foveal::openxr

#pragma once
// The head pose (docs/conventions.md, "Head pose"): where the head is in the tracking
// space and which way it faces, on the runtime's axes (x right, y up, -z forward).
//
// All functions here are pure and thread-safe; none throws.
#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "foveal/core/clock.hpp"

namespace foveal {

/// A rigid transform from the head frame to the tracking (world) frame:
/// p_world = orientation · p_head + position_m. The head frame is the gaze data's head
/// frame (origin between the eyes, x right, y up, -z forward).
struct Pose {
  glm::vec3 position_m{0.0f};                     ///< the head frame's origin, metres
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};  ///< unit quaternion, constructed (w, x, y, z)

  bool operator==(const Pose&) const = default;
};

/// A pose at a time: on the runtime clock (CLOCK_MONOTONIC ns) in the runtime, on the
/// log's own time base in files.
struct TimedPose {
  TimeNs t_ns = 0;
  Pose pose{};
};

/// The head pose a gaze sample carries when its source knows it (a log with head-pose
/// columns, later an HMD driver). Its time is the sample's `t_ns`.
struct HeadPose {
  bool valid = false;  ///< false: no pose; `pose` then holds the identity and means nothing
  Pose pose{};

  bool operator==(const HeadPose&) const = default;
};

/// How far from 1 a stored quaternion's norm may be (logs, drivers): six significant
/// digits of each component already keep it within 1e-5; 1e-3 leaves room for float
/// sums and rejects what is clearly not a rotation.
constexpr float kUnitQuaternionTolerance = 1e-3f;

/// Every component finite.
bool is_finite(const Pose& p);
/// |q|, computed in double.
double quaternion_norm(const glm::quat& q);
/// Finite and | |q| - 1 | <= kUnitQuaternionTolerance.
bool is_unit(const glm::quat& q);

/// `q` scaled to unit length, or `q` itself, bit for bit, when its norm is already 1 to
/// float precision (so a stored pose passes through a track or the compositor unchanged).
/// `q` must be finite and non-zero.
glm::quat renormalized(const glm::quat& q);

/// `a` after `b`: p -> a(b(p)). compose(a, identity) == a exactly.
Pose compose(const Pose& a, const Pose& b);
/// The inverse transform (orientation conjugated; the orientation must be unit).
Pose inverse(const Pose& p);
/// `p` expressed in `anchor`'s frame: inverse(anchor) ∘ p. Exactly the identity when
/// p == anchor, so a camera driven by relative poses starts exactly at its base view.
Pose relative_to(const Pose& anchor, const Pose& p);
/// Between `a` (u = 0, returned exactly) and `b` (u = 1, returned exactly): position
/// lerped, orientation slerped along the shorter arc (q and -q are the same rotation)
/// and renormalised. u is clamped to [0, 1].
Pose interpolate(const Pose& a, const Pose& b, double u);

}  // namespace foveal

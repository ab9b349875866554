#pragma once
// Camera paths for `foveal bench --flicker` (docs/stability.md, "Flicker under a moving
// camera"): the head pose, relative to the scene's view (render::FrameParams::head), at a
// time since the run's first frame. Orbit and dolly are about a pivot on the start view's
// line of sight; both go back and forth between fixed ends at a constant speed, so a long
// run stays near the scene's view instead of walking through walls.
//
// Pure functions; none throws.
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "foveal/core/error.hpp"
#include "foveal/core/pose.hpp"

namespace foveal::bench {

struct CameraPath {
  /// static: the scene's view; orbit: around the pivot, about the head's up axis, facing
  /// it; dolly: along the line of sight towards the pivot and back; recorded: the gaze
  /// log's own head pose (poses come from the log, not from camera_pose()).
  enum class Kind { still, orbit, dolly, recorded };
  Kind kind = Kind::still;
  /// orbit: degrees per second of turn about the pivot; dolly: metres per second.
  /// 0: not given (with_default_speed sets it).
  double speed = 0.0;

  /// The spec parse_camera_path reads back to this path: "static", "orbit:30", "dolly"
  /// (no speed given yet), ...
  std::string text() const;
  bool operator==(const CameraPath&) const = default;
};

/// An orbit swings between -kOrbitHalfRangeDeg and +kOrbitHalfRangeDeg about the pivot.
constexpr double kOrbitHalfRangeDeg = 20.0;
constexpr double kDefaultOrbitDegPerS = 30.0;
/// A dolly goes from the start to this share of the pivot distance and back.
constexpr double kDollyReach = 0.5;
/// Default dolly speed, in pivot distances per second.
constexpr double kDefaultDollyPivotsPerS = 0.25;

/// "static", "orbit[:DEG_PER_S]", "dolly[:M_PER_S]" or "recorded". Errors (bad_input)
/// name `option` and the spec.
Result<CameraPath> parse_camera_path(const std::string& spec, const std::string& option = "--camera-path");

/// `path` with its speed set where the spec gave none: kDefaultOrbitDegPerS, or
/// kDefaultDollyPivotsPerS pivot distances per second for a dolly.
CameraPath with_default_speed(CameraPath path, double pivot_m);

/// Where the scene's bounds lie from its view, in metres (scene units / units_per_meter):
/// how far ahead of the head their centre is along the line of sight (-z of
/// head_to_world; negative behind), and their radius (half the diagonal).
struct ViewGeometry {
  double ahead_m = 0, radius_m = 0;
};
ViewGeometry view_geometry(const glm::mat4& head_to_world, float units_per_meter, const glm::vec3& bounds_center, float bounds_radius);

/// The pivot's distance from the head when none is given: how far ahead the bounds'
/// centre is, at least half their radius and at most their radius (a camera inside a large
/// interior turns about a point in the room, not across it).
double default_pivot_m(const ViewGeometry& g);

/// How far to move forward along the line of sight so that the bounds' sphere fills the
/// view (its centre 1.05 radii ahead, as foveal_render_bench's FOVEAL_BENCH_FILL does for
/// a view that looks at it); 0 when the head is already that close.
double fill_offset_m(const ViewGeometry& g);

/// The head pose (head frame of the scene's view, metres) at `t_s` seconds along `path`
/// with the pivot `pivot_m` metres ahead. The identity exactly at t = 0 and for static.
/// recorded is the caller's: the identity here.
Pose camera_pose(const CameraPath& path, double pivot_m, double t_s);

/// A triangle wave of the distance `s` travelled: 0 at s = 0, rising at slope 1 to `hi`,
/// falling to `lo`, and so on (lo <= 0 <= hi, hi > lo).
double back_and_forth(double s, double lo, double hi);

}  // namespace foveal::bench

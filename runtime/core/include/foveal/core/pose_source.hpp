#pragma once
// The seam between whatever knows the head pose (the gaze thread replaying a log with
// poses, a headset's own tracking through runtime/head's pose thread) and the renderer,
// which asks once per frame. The
// compositor only ever sees the Pose it is handed (render::FrameParams::head), so a new
// pose source plugs in here without touching it.
#include "foveal/core/clock.hpp"
#include "foveal/core/pose.hpp"

namespace foveal {

/// The answer to "where was the head at time t?".
struct PoseAt {
  bool valid = false;  ///< false: the source has no pose yet; both poses hold the identity
  Pose pose{};         ///< in the tracking frame (what a log or frames.csv records)
  /// `pose` relative to the source's anchor, its first pose: relative_to(anchor, pose).
  /// This is what moves the camera (render::FrameParams::head): the first pose shows
  /// the scene's own view.
  Pose relative{};
  /// The time the pose is for (the time asked, or a prediction's display time); 0 when invalid.
  TimeNs t_ns = 0;
};

/// Thread safety: pose_at() is called from the render thread while producers run, so
/// every implementation is thread-safe and never blocks for longer than a short copy.
class PoseSource {
 public:
  virtual ~PoseSource() = default;
  /// The pose at runtime time `t_ns` (CLOCK_MONOTONIC ns, docs/conventions.md).
  virtual PoseAt pose_at(TimeNs t_ns) const = 0;
};

}  // namespace foveal

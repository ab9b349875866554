#pragma once
// Where `foveal render` puts the head: a pose given on the command line (--head) or the
// pose and fovea a native gaze log has at a time (--log, --at), so that a recorded
// sequence can be rendered frame by frame as `bench --gaze` renders it (docs/scenes.md,
// "Camera").
#include <array>
#include <optional>
#include <string>

#include <glm/vec2.hpp>

#include "foveal/core/display_model.hpp"
#include "foveal/core/error.hpp"
#include "foveal/core/pose.hpp"

namespace foveal::cmd {

/// "X,Y,Z,QW,QX,QY,QZ": the head's pose relative to the scene's view (render::FrameParams::head),
/// metres and a unit quaternion (w first, docs/conventions.md "Head pose"). Refused, naming
/// `what` and the part: not seven numbers, a non-finite number, a quaternion whose norm is
/// off 1 by more than kUnitQuaternionTolerance. A quaternion within it is renormalised.
Result<Pose> parse_head_pose(const std::string& s, const std::string& what);

/// A log's frame at a time, as `bench --gaze` computes it for a frame that starts then.
struct LogFrame {
  double sample_s = 0;  ///< the latest sample at or before the time (s from the first sample): its fovea and pose
  double duration_s = 0;  ///< the last sample's time from the first
  Pose relative{};      ///< its head pose relative to the log's first pose
  std::array<glm::dvec2, 2> fovea{};  ///< filtered, normalised (origin top-left), left and right
};

/// The frame of native log `path` at `at_s` seconds after its first sample: the samples up
/// to then through foveald's gaze pipeline (default filter) on `model`, and the head pose of
/// the latest of them relative to the log's first pose. Errors name the log: unreadable, no
/// head pose, `at_s` outside the log's samples, no pose yet at that time.
Result<LogFrame> log_frame_at(const std::string& path, double at_s, const DisplayModel& model);

}  // namespace foveal::cmd

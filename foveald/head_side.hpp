#pragma once
// foveald's head pose (docs/daemon.md, "Head pose"; docs/headset.md): where each
// frame's camera comes from.
//   recorded  the gaze source's own poses (a v2 log), sampled at the frame's gaze time
//   static    the scene's own view
//   psvr2, vive[:PATH], auto  a headset's tracking, read on a pose thread (HeadTracker)
//             and predicted to the frame's expected display time: one refresh after
//             the frame starts; predicted-vs-measured errors go to summary.json
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "foveal/core/gaze_sample.hpp"
#include "foveal/core/pose_track.hpp"
#include "foveal/drivers/probe.hpp"
#include "foveal/runtime/head_tracker.hpp"
#include "foveal/runtime/pose_prediction.hpp"

namespace foveal::daemon {

class HeadSide {
 public:
  /// `head`: the --head value ("" = recorded when the gaze source has poses, else
  /// static). A device is made and opened once right away, so that a headset's own
  /// display model is known before the compositor starts; one that is not there yet is
  /// waited for by the pose thread. Errors: bad_input for an unknown spec, or
  /// `recorded` with a source that has no poses.
  static Result<std::unique_ptr<HeadSide>> create(const std::string& head, bool source_has_pose,
                                                  const std::string& source_text, const probe::SourceOptions& options);
  ~HeadSide();

  const std::string& mode() const { return mode_; }
  bool recorded() const { return mode_ == "recorded"; }
  /// The display model the headset itself reported at the first open (Vive).
  const std::optional<probe::HeadsetDisplay>& headset_display() const { return display_; }

  /// Starts the pose thread (devices only).
  void start();
  /// Stops it; after this, json() includes the driver's counters.
  void stop();

  /// Gaze thread: a sample of a source with poses (recorded mode).
  void push_recorded(const GazeSample& s);
  /// Render thread: the pose for a frame whose gaze sample is at `gaze_t_ns`, starting
  /// now, on an output refreshing at `refresh_hz`.
  PoseAt for_frame(TimeNs gaze_t_ns, double refresh_hz);
  /// Any thread: mode, state, counts, prediction errors.
  nlohmann::json json() const;

 private:
  HeadSide() = default;

  std::string mode_;
  PoseTrack recorded_;
  std::optional<probe::OpenedPoseDevice> device_;
  std::unique_ptr<HeadTracker> tracker_;
  std::optional<probe::HeadsetDisplay> display_;
  bool stopped_ = false;
  HeadState state_at_stop_ = HeadState::stopped;
  mutable std::mutex prediction_mutex_;  // render thread writes, control thread reads
  PredictionErrors prediction_;
  double refresh_hz_ = 0;
};

}  // namespace foveal::daemon

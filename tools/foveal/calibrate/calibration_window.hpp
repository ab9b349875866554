#pragma once
// `foveal calibrate`'s in-headset mode: drives the calibration state machine from a
// GLFW window (fullscreen on the HMD's monitor) with the keyboard or a gamepad.
#include <string>
#include <vector>

#include "foveal/core/gaze_source.hpp"
#include "foveal/runtime/calibration.hpp"

namespace foveal::cmd {

struct CalibrationWindowOptions {
  std::string monitor;  ///< fullscreen on this monitor; empty: a window
  std::string scene;    ///< what the comparisons show; empty: the bundled Dungeon
  double flip_s = 1.0;  ///< comparisons alternate full and test images this often
  /// A started gaze source, read while the validation trials show their fixation target
  /// (calibrate --gaze); null: none.
  GazeSource* gaze = nullptr;
};

/// The gaze read during the validation trials, and each trial's fixation window (from
/// its first frame plus a settling time to its answer) on the samples' clock.
struct ValidationGaze {
  static constexpr TimeNs kSettleNs = 500'000'000;  ///< the eyes reach the target first
  std::vector<GazeSample> samples;
  std::vector<std::pair<TimeNs, TimeNs>> fixations;
};

/// What the answers were judged on: the frames' size (the display model's) and the size
/// they were shown at. A window smaller than the frames shrinks them, which hides the
/// foveation being judged: sigma then comes out too high.
struct CalibrationDisplay {
  int frame_width = 0, frame_height = 0;
  int shown_width = 0, shown_height = 0;
  std::string monitor;  ///< empty: a window on the desktop
  double scale() const { return frame_width > 0 ? static_cast<double>(shown_width) / frame_width : 0.0; }
};

/// Each prompt's instruction, for the picture and the terminal: the stage, the trial, the
/// question and the keys.
std::string calibration_instruction(const CalibrationPrompt& p);

/// Runs `cal` to completion, telling each step in the picture and on stderr. Errors: no display or window (unsupported), the user quit
/// (Esc or closing the window: bad_input, nothing is saved), GL failures.
Status run_calibration_window(Calibration& cal, const CalibrationWindowOptions& o, ValidationGaze* gaze = nullptr,
                              CalibrationDisplay* display = nullptr);

}  // namespace foveal::cmd

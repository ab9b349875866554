#pragma once
// `foveal calibrate`'s in-headset mode: drives the calibration state machine from a
// GLFW window (fullscreen on the HMD's monitor) with the keyboard or a gamepad.
#include <string>

#include "foveal/runtime/calibration.hpp"

namespace foveal::cmd {

struct CalibrationWindowOptions {
  std::string monitor;  ///< fullscreen on this monitor; empty: a window
  std::string scene;    ///< what the comparisons show; empty: the bundled Dungeon
  double flip_s = 1.0;  ///< comparisons alternate full and test images this often
};

/// Runs `cal` to completion. Errors: no display or window (unsupported), the user quit
/// (Esc or closing the window: bad_input, nothing is saved), GL failures.
Status run_calibration_window(Calibration& cal, const CalibrationWindowOptions& o);

}  // namespace foveal::cmd

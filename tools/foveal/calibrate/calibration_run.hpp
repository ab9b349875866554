#pragma once
// What `foveal calibrate` does once its options are parsed: the calibration state machine
// answered in the headset window or from an answers file, the validation trials' gaze
// quality (a log, or a source read live), and the result saved into a profile
// (docs/calibration.md).
#include <string>

#include "foveal/core/error.hpp"

namespace foveal::cmd {

struct CalibrateRequest {
  std::string profile;       ///< profile to update; empty: the active one
  std::string answers;       ///< scripted mode's answers file; empty: the in-headset window
  std::string monitor;       ///< in-headset mode: fullscreen on this monitor
  std::string scene;         ///< in-headset mode: the comparisons' scene; empty: the bundled Dungeon
  std::string gaze_log;      ///< a native gaze log recorded during the validation trials
  std::string gaze_targets;  ///< its targets CSV; empty: all straight ahead
  std::string gaze;          ///< in-headset mode: a gaze source spec read during the validation trials
  bool json = false, dry_run = false;
};

/// Runs the calibration, prints the result (text or JSON) and saves it into the profile
/// unless a dry run or the validation failed. Errors: a bad gaze log (before anything is
/// asked), no display, the user quit, a bad answers file, the profile store; a failed
/// validation is bad_input after the result is printed.
Status run_calibration(const CalibrateRequest& a);

}  // namespace foveal::cmd

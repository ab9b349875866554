#pragma once
// foveald's command-line options.
#include <optional>
#include <string>

namespace foveal::daemon {

struct Options {
  std::string replay;         ///< gaze log; empty = the bundled recording
  std::string display;        ///< display-model JSON; empty = from the profile / default
  std::string out = "foveald-out";
  std::string profile;        ///< empty = the active profile (or built-in defaults)
  std::string control;        ///< control socket path; empty = default
  bool no_control = false;
  bool shm = true;            ///< publish the fovea in shared memory
  double speed = 1.0;
  bool loop = false;
  std::optional<double> start_s, end_s;
  bool headless = true;
  bool json = false;
  int verbosity = 0;          ///< +1 per -v, -1 per -q
  int rt_priority = 0;        ///< > 0: SCHED_FIFO for the gaze thread
};

}  // namespace foveal::daemon

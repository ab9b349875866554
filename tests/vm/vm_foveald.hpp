#pragma once
// foveald as the guest's live checks run it (vm_live.cpp, vm_hmd.cpp): started with its
// outputs and a control socket of its own, asked for its status over that socket while
// the devices come and go, and stopped with SIGTERM.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/core/clock.hpp"

namespace foveal::vmtest {

class FovealdRun {
 public:
  /// `args` (foveald and its options) gain --out OUT and --control OUT-run/control.sock
  /// (a directory of its own: foveald refuses one others may enter, as /tmp); the
  /// command line is printed as "TAG: ...".
  FovealdRun(std::vector<std::string> args, const std::string& out, const char* tag);
  /// Spawns it with stdout and stderr in OUT.log; false if it cannot start.
  bool start();
  bool started() const { return pid_ >= 0; }
  /// One status request (2 s timeout); on success status() is its reply.
  bool ask();
  const nlohmann::json& status() const { return status_; }
  /// Started and not exited (does not block).
  bool alive();
  struct Stopped {
    int rc = -1;          ///< the exit code, or 128 + the signal
    TimeNs t_term = 0;    ///< when SIGTERM was sent (CLOCK_MONOTONIC)
    double term_ms = 0;   ///< from SIGTERM to its end
    std::string problem;  ///< non-empty when it had to be killed
  };
  /// SIGTERM, then up to 10 s for it to end, then SIGKILL.
  Stopped stop();
  const std::string& program() const { return args_.front(); }

 private:
  std::vector<std::string> args_;
  std::string log_, socket_;
  int pid_ = -1, wstatus_ = 0;
  bool gone_ = false;
  nlohmann::json status_;
};

}  // namespace foveal::vmtest

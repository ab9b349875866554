#include "vm_foveald.hpp"

#include <signal.h>
#include <sys/wait.h>

#include <cstdio>

#include "foveal/runtime/control_server.hpp"
#include "vm_guest.hpp"

namespace foveal::vmtest {

FovealdRun::FovealdRun(std::vector<std::string> args, const std::string& out, const char* tag)
    : args_(std::move(args)), log_(out + ".log"), socket_(out + "-run/control.sock") {
  args_.insert(args_.end(), {"--out", out, "--control", socket_});
  std::string cmdline;
  for (const std::string& a : args_) cmdline += a + " ";
  std::printf("%s: %s\n", tag, cmdline.c_str());
  std::fflush(stdout);
}

bool FovealdRun::start() {
  pid_ = spawn_logged(args_, log_);
  return pid_ >= 0;
}

bool FovealdRun::ask() {
  auto r = control_request(socket_, {{"cmd", "status"}}, 2000);
  if (r) status_ = *r;
  return static_cast<bool>(r);
}

bool FovealdRun::alive() {
  if (!gone_) gone_ = pid_ < 0 || exited(pid_, wstatus_);
  return !gone_;
}

FovealdRun::Stopped FovealdRun::stop() {
  Stopped s;
  if (alive()) ::kill(pid_, SIGTERM);
  s.t_term = monotonic_now_ns();
  if (!wait_for([&] { return !alive(); }, 10 * kNsPerSec)) {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, &wstatus_, 0);
    s.problem = "foveald did not end within 10 s of SIGTERM";
  }
  s.term_ms = static_cast<double>(monotonic_now_ns() - s.t_term) / 1e6;
  s.rc = WIFEXITED(wstatus_) ? WEXITSTATUS(wstatus_) : 128 + WTERMSIG(wstatus_);
  return s;
}

}  // namespace foveal::vmtest

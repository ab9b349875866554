#pragma once
// Helpers shared by the tests: temporary directories, running the CLI, reading files.
#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>

namespace foveal::test {

/// A fresh directory under $TMPDIR, removed with everything in it at scope exit.
class TempDir {
 public:
  TempDir() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "foveal-test-XXXXXX").string();
    if (!::mkdtemp(tmpl.data())) std::abort();
    path_ = tmpl;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string path(const std::string& name = "") const { return name.empty() ? path_ : path_ + "/" + name; }

 private:
  std::string path_;
};

/// Bounds for "returns instead of blocking" and "exits on SIGTERM": far above the timeout
/// under test and any delay a loaded 2-core machine adds, far below forever. A test checks
/// that the event happened; how fast it happens is for benchmarks and printed figures
/// (docs/testing.md, "Events, not times").
inline constexpr long long kReturnsWithinNs = 10'000'000'000LL;
inline constexpr int kExitsWithinMs = 30000;
/// Hang guard for waiting on an event a test causes (a sample, a frame, a state, a line
/// in a log): it is waited for, polled, for at most this long on the monotonic clock.
inline constexpr int kEventWithinMs = 60000;

/// Polls `ready` every `poll_ms` until it holds or `within_ms` passed (a hang guard, not
/// a timing); its last value. The deadline is on the clock, so a loaded machine that
/// stretches each poll's sleep does not stretch the guard.
template <class Ready>
bool eventually(Ready&& ready, int within_ms = kEventWithinMs, int poll_ms = 5) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(within_ms);
  while (!ready()) {
    if (std::chrono::steady_clock::now() >= until) return ready();
    std::this_thread::sleep_for(std::chrono::milliseconds(poll_ms));
  }
  return true;
}

/// Waits up to `ms` for child `pid` to exit: its exit code (128 + the signal when
/// killed), or -1 while it still runs (the child is then left as it is).
inline int wait_for_exit(pid_t pid, int ms) {
  for (int i = 0; i < ms; ++i) {
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return -1;
}

/// Waits up to `ms` until every thread of `pid` is stopped (state T in /proc): kill(SIGSTOP)
/// returns before a thread preempted inside a syscall (an accept(), say) has finished it.
/// True once all are stopped.
inline bool wait_until_stopped(pid_t pid, int ms) {
  const std::filesystem::path tasks = "/proc/" + std::to_string(pid) + "/task";
  for (int i = 0; i < ms; ++i) {
    bool all = true;
    std::error_code ec;
    for (const auto& t : std::filesystem::directory_iterator(tasks, ec)) {
      std::ifstream in(t.path() / "stat");
      std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      const auto paren = stat.rfind(')');  // the name may hold spaces and parentheses
      if (paren == std::string::npos || paren + 2 >= stat.size() || stat[paren + 2] != 'T') all = false;
    }
    if (!ec && all) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

inline std::string source_path(const std::string& rel) { return std::string(FOVEAL_SOURCE_DIR) + "/" + rel; }
inline std::string bin(const std::string& name) { return std::string(FOVEAL_BIN_DIR) + "/" + name; }

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline void write_file(const std::string& path, const std::string& data) {
  std::ofstream out(path, std::ios::binary);
  out << data;
}

/// Runs a shell command, capturing stdout and stderr; returns the exit code.
struct RunResult {
  int exit_code = -1;
  std::string out, err;
};
inline RunResult run(const std::string& cmd) {
  TempDir d;
  const std::string o = d.path("out"), e = d.path("err");
  const int rc = std::system((cmd + " >" + o + " 2>" + e).c_str());
  RunResult r;
  r.exit_code = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  r.out = read_file(o);
  r.err = read_file(e);
  return r;
}

}  // namespace foveal::test

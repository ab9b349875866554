// The runtime probe in a child process: an OpenXR runtime is someone else's code,
// loaded with whatever it links, and it may crash, hang, or (through XR_RUNTIME_JSON
// naming a FIFO) make the loader wait for ever. The child loads it with its stdout and
// stderr on a pipe and writes its answer as JSON on another; the parent waits at most
// the time limit, then kills it. No shell and no exec: the child is a fork.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>

#include <nlohmann/json.hpp>

#include "foveal/core/json_file.hpp"
#include "foveal/core/json_text.hpp"
#include "probe.hpp"

namespace foveal::openxr {

namespace {

constexpr std::size_t kMaxAnswerBytes = 64 * 1024;
constexpr std::size_t kMaxLogBytes = 256 * 1024;  // the log's end is kept past this

nlohmann::json to_json(const RuntimeGaze& g) {
  return {{"probed", g.probed},
          {"runtime_failed", g.runtime_failed},
          {"message", g.message},
          {"runtime_name", g.runtime_name},
          {"system_name", g.system_name},
          {"lists", g.lists_eye_gaze_interaction},
          {"supports", g.supports_eye_gaze_interaction}};
}

bool from_json(const nlohmann::json& j, RuntimeGaze& g) {
  if (!j.is_object()) return false;
  auto text = [&](const char* k, std::string& out) {
    if (!j.contains(k) || !j[k].is_string()) return false;
    out = j[k].get<std::string>();
    return true;
  };
  auto flag = [&](const char* k, bool& out) {
    if (!j.contains(k) || !j[k].is_boolean()) return false;
    out = j[k].get<bool>();
    return true;
  };
  return flag("probed", g.probed) && flag("runtime_failed", g.runtime_failed) && text("message", g.message) &&
         text("runtime_name", g.runtime_name) && text("system_name", g.system_name) &&
         flag("lists", g.lists_eye_gaze_interaction) && flag("supports", g.supports_eye_gaze_interaction);
}

void write_all(int fd, const std::string& s) {
  std::size_t done = 0;
  while (done < s.size()) {
    const ssize_t n = ::write(fd, s.data() + done, s.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += static_cast<std::size_t>(n);
  }
}

[[noreturn]] void run_child(pid_t parent, int answer_fd, int log_fd) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // never outlive `foveal openxr` (Ctrl-C, a kill)
  if (::getppid() != parent) ::_exit(120);
  // A crash in the runtime is reported by its signal: no sanitizer or other handler
  // inherited from the parent turns it into an exit status.
  for (int sig : {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT, SIGPIPE}) ::signal(sig, SIG_DFL);
  const int null_fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  if (null_fd >= 0) ::dup2(null_fd, STDIN_FILENO);
  ::dup2(log_fd, STDOUT_FILENO);
  ::dup2(log_fd, STDERR_FILENO);
  try {
    const RuntimeGaze g = probe_runtime_here();
    write_all(answer_fd, json_text(to_json(g)));
  } catch (...) {
    ::_exit(121);  // the parent reports an exit without an answer
  }
  ::_exit(0);  // no atexit handlers, no flushing of the parent's stdio buffers
}

/// Appends what `fd` holds now; false at end of file or on an error.
bool drain(int fd, std::string& into, std::size_t max_bytes, bool keep_end) {
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n > 0) {
      into.append(buf, static_cast<std::size_t>(n));
      if (into.size() > max_bytes) {
        if (keep_end) into.erase(0, into.size() - max_bytes);
        else into.resize(max_bytes);
      }
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    return n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK);
  }
}

std::string seconds_text(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", s);
  return buf;
}

}  // namespace

RuntimeGaze probe_runtime_in_child(double timeout_s) {
  RuntimeGaze g;
  int answer[2], log[2];
  if (::pipe2(answer, O_CLOEXEC) != 0) {
    g.message = std::string("cannot start the probe: ") + std::strerror(errno);
    return g;
  }
  if (::pipe2(log, O_CLOEXEC) != 0) {
    g.message = std::string("cannot start the probe: ") + std::strerror(errno);
    ::close(answer[0]);
    ::close(answer[1]);
    return g;
  }
  std::fflush(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(answer[0]);
    ::close(log[0]);
    run_child(parent, answer[1], log[1]);
  }
  const int fork_errno = errno;
  ::close(answer[1]);
  ::close(log[1]);
  if (pid < 0) {
    ::close(answer[0]);
    ::close(log[0]);
    g.message = std::string("cannot start the probe: ") + std::strerror(fork_errno);
    return g;
  }
  for (int fd : {answer[0], log[0]}) ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
  // A pidfd says when the child has exited, even where something it started still holds
  // the pipes open; without one (kernels before 5.3) the pipes' end of file and a
  // waitpid poll say it.
  const int pidfd = static_cast<int>(::syscall(SYS_pidfd_open, pid, 0));

  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_s));
  std::string answer_text;
  bool answer_open = true, log_open = true, exited = false, timed_out = false;
  int status = 0;
  while (!exited) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) {
      timed_out = true;
      break;
    }
    pollfd fds[3] = {{answer_open ? answer[0] : -1, POLLIN, 0}, {log_open ? log[0] : -1, POLLIN, 0}, {pidfd, POLLIN, 0}};
    const int wait_ms = pidfd >= 0 ? static_cast<int>(std::min<long long>(left, 60'000)) : static_cast<int>(std::min<long long>(left, 10));
    const int n = ::poll(fds, 3, wait_ms);
    if (n < 0 && errno != EINTR) break;
    if (answer_open && fds[0].revents) answer_open = drain(answer[0], answer_text, kMaxAnswerBytes, false);
    if (log_open && fds[1].revents) log_open = drain(log[0], g.log, kMaxLogBytes, true);
    if (pidfd >= 0 ? (fds[2].revents != 0) : (!answer_open || !log_open || n == 0)) {
      const pid_t w = ::waitpid(pid, &status, pidfd >= 0 ? 0 : WNOHANG);
      exited = w == pid;
    }
  }
  if (!exited) {
    ::kill(pid, SIGKILL);
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
  }
  // What the child wrote before it ended is still in the pipes.
  drain(answer[0], answer_text, kMaxAnswerBytes, false);
  drain(log[0], g.log, kMaxLogBytes, true);
  for (int fd : {answer[0], log[0], pidfd})
    if (fd >= 0) ::close(fd);

  if (timed_out) {
    g.runtime_failed = true;
    g.message = "the runtime did not answer in " + seconds_text(timeout_s) + " s (the probe was stopped)";
    return g;
  }
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    g.runtime_failed = true;
    g.message = "the runtime crashed (signal " + std::to_string(sig) + ", " + ::strsignal(sig) + ")";
    return g;
  }
  RuntimeGaze answered;
  if (!exited || !WIFEXITED(status) || WEXITSTATUS(status) != 0 ||
      !from_json(parse_json_or_discarded(answer_text, JsonLimits{kMaxAnswerBytes, 4}), answered)) {
    g.runtime_failed = true;
    g.message = "the probe ended without an answer (exit status " +
                std::to_string(exited && WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")";
    return g;
  }
  answered.log = std::move(g.log);
  return answered;
}

}  // namespace foveal::openxr

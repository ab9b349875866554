#include "layer_log.hpp"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <mutex>

namespace foveal::openxr {

namespace {

std::atomic<std::uint64_t> g_dropped{0};

/// Where lines go: -1 nowhere, else a descriptor that never blocks (or a socket, sent
/// with MSG_DONTWAIT).
struct Sink {
  int fd = -1;
  bool socket = false;
};

Sink open_sink() {
  Sink s;
  struct stat st {};
  if (::fstat(STDERR_FILENO, &st) != 0) return s;
  if (S_ISSOCK(st.st_mode)) {
    s.fd = STDERR_FILENO;  // the send flags make it non-blocking; the app's flags stay
    s.socket = true;
    return s;
  }
  if (S_ISREG(st.st_mode)) {
    // A file never blocks a write, and the app's own offset must move past the line
    // (a description of our own would write where the app then overwrites).
    s.fd = STDERR_FILENO;
    return s;
  }
  // A new open file description of the same pipe or terminal: O_NONBLOCK on it leaves
  // the app's descriptor as it was.
  s.fd = ::open("/proc/self/fd/2", O_WRONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  return s;
}

const Sink& sink() {
  static std::once_flag once;
  static Sink s;
  std::call_once(once, [] { s = open_sink(); });
  return s;
}

/// One write of a whole line. A pipe whose reader is gone raises SIGPIPE: blocked on
/// this thread for the write, and taken back if the write raised it.
bool write_line(const Sink& s, const char* text, std::size_t n) {
  if (s.socket) return ::send(s.fd, text, n, MSG_DONTWAIT | MSG_NOSIGNAL) == static_cast<ssize_t>(n);
  sigset_t pipe_only, old;
  sigemptyset(&pipe_only);
  sigaddset(&pipe_only, SIGPIPE);
  sigset_t pending;
  sigemptyset(&pending);
  const bool was_pending = ::sigpending(&pending) == 0 && sigismember(&pending, SIGPIPE);
  ::pthread_sigmask(SIG_BLOCK, &pipe_only, &old);
  ssize_t w;
  do w = ::write(s.fd, text, n);
  while (w < 0 && errno == EINTR);
  const int write_errno = errno;
  if (w < 0 && write_errno == EPIPE && !was_pending) {
    const timespec zero{0, 0};
    ::sigtimedwait(&pipe_only, nullptr, &zero);
  }
  ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
  return w == static_cast<ssize_t>(n);
}

}  // namespace

void log_line(const char* text) {
  const Sink& s = sink();
  char line[512];
  const int n = std::snprintf(line, sizeof line, "foveal-openxr: %s\n", text);
  if (s.fd < 0 || n <= 0) {
    g_dropped.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  std::size_t len = static_cast<std::size_t>(n);
  if (len >= sizeof line) {  // cut short: still one whole line
    len = sizeof line - 1;
    line[len - 1] = '\n';
  }
  // A pipe takes a line of at most PIPE_BUF bytes whole or not at all (EAGAIN).
  if (!write_line(s, line, len)) g_dropped.fetch_add(1, std::memory_order_relaxed);
}

std::uint64_t log_lines_dropped() { return g_dropped.load(std::memory_order_relaxed); }

}  // namespace foveal::openxr

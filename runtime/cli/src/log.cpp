#include "foveal/runtime/log.hpp"

#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <climits>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <mutex>
#include <thread>

namespace foveal::log {

namespace {
std::atomic<int> g_level{static_cast<int>(Level::info)};
const char* g_program = "foveal";
const char* const kNames[] = {"error", "warn", "info", "debug"};

/// How a write to a standard descriptor is kept from waiting for its reader.
enum class Guard : int {
  none,     ///< a regular file, or our own O_NONBLOCK description: write() as it is
  socket,   ///< send(MSG_DONTWAIT): a socket's description cannot be reopened
  polled,   ///< shared and blocking (reopen refused): write only what poll() says fits
};
std::atomic<int> g_guard[3]{};  // by descriptor number (1 and 2 used)

/// Makes `fd` (1 or 2) a description of its own, opened O_NONBLOCK, when it is a pipe, a
/// FIFO or a terminal: setting O_NONBLOCK on the inherited description would change it
/// for the shell and every other process that shares it. From then on no write to the
/// descriptor waits for a reader, whoever makes it (our lines, a library's fprintf, the
/// exit-time flush of stdio): a write that finds no room fails with EAGAIN.
Guard make_own_nonblocking(int fd) {
  struct stat st{};
  if (::fstat(fd, &st) != 0) return Guard::none;  // closed: writes fail at once
  if (S_ISSOCK(st.st_mode)) return Guard::socket;
  if (!S_ISFIFO(st.st_mode) && !S_ISCHR(st.st_mode)) return Guard::none;  // a file never waits for a reader
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0 && (flags & O_NONBLOCK)) return Guard::none;
  char path[32];
  std::snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
  // O_NOCTTY: a terminal must not become our controlling one. A FIFO without a reader
  // (ENXIO) or another user's pipe (EACCES) keeps its description and is polled.
  const int own = ::open(path, O_WRONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (own < 0) return Guard::polled;
  const bool moved = ::dup2(own, fd) == fd;  // dup2 clears O_CLOEXEC: children inherit it as before
  ::close(own);
  return moved ? Guard::none : Guard::polled;
}

/// Writes some of [p, p + n) to `fd` without waiting: the bytes written, 0 when there is
/// no room now, -1 when the descriptor is broken (a reader that is gone, a closed fd).
ssize_t try_write(int fd, const char* p, std::size_t n) {
  const auto guard = static_cast<Guard>(g_guard[fd].load(std::memory_order_relaxed));
  for (;;) {
    ssize_t r;
    if (guard == Guard::socket) {
      r = ::send(fd, p, n, MSG_DONTWAIT | MSG_NOSIGNAL);
      if (r < 0 && errno == ENOTSOCK) r = ::write(fd, p, n);
    } else if (guard == Guard::polled) {
      pollfd pf{fd, POLLOUT, 0};
      if (::poll(&pf, 1, 0) < 0) {
        if (errno == EINTR) continue;
        return -1;
      }
      if (pf.revents & (POLLERR | POLLHUP | POLLNVAL)) return -1;
      if (!(pf.revents & POLLOUT)) return 0;
      r = ::write(fd, p, std::min<std::size_t>(n, PIPE_BUF));  // up to PIPE_BUF fits whole once POLLOUT
    } else {
      r = ::write(fd, p, n);
    }
    if (r >= 0) return r;
    if (errno == EINTR) continue;
    return errno == EAGAIN || errno == EWOULDBLOCK ? 0 : -1;
  }
}

/// Waits up to `ms` for room in `fd` (in poll(), never in write()).
void wait_for_room(int fd, int ms) {
  pollfd pf{fd, POLLOUT, 0};
  if (::poll(&pf, 1, ms) == 1 && (pf.revents & POLLOUT)) {
    // Some descriptors (a terminal) say POLLOUT and still answer EAGAIN: no busy loop.
    timespec ts{0, 2'000'000};
    ::nanosleep(&ts, nullptr);
  }
}

using Clock = std::chrono::steady_clock;

/// Writes all of `text` to `fd`, waiting for room while the reader takes some within
/// `stall_ms` and at most `total_ms` in all (< 0: no limit); true when all of it went.
bool write_waiting(int fd, const std::string& text, int stall_ms, int total_ms) {
  const auto start = Clock::now();
  auto last_progress = start;
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = try_write(fd, text.data() + done, text.size() - done);
    const auto now = Clock::now();
    if (n < 0) return false;
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      last_progress = now;
      continue;
    }
    const auto since = [now](Clock::time_point t) {
      return static_cast<int>(std::chrono::duration_cast<std::chrono::milliseconds>(now - t).count());
    };
    if (stall_ms >= 0 && since(last_progress) >= stall_ms) return false;
    if (total_ms >= 0 && since(start) >= total_ms) return false;
    wait_for_room(fd, 50);
  }
  return true;
}

std::uint64_t line_count(const std::string& text) {
  const auto n = static_cast<std::uint64_t>(std::count(text.begin(), text.end(), '\n'));
  return std::max<std::uint64_t>(n, 1);
}

/// The queue between the threads that log and the one that writes stderr.
struct Queue {
  std::mutex m;
  std::condition_variable wake, progress;
  std::deque<std::string> texts;
  std::size_t bytes = 0;           ///< queued, not yet written
  bool writing = false;            ///< the writer holds a text outside the queue
  std::uint64_t written = 0;       ///< texts written (or lost) so far: flush() sees progress
  std::atomic<std::uint64_t> dropped{0};
};
// Set once by start_writer_thread() and never freed: at exit the writer may still wait
// for room in a pipe nobody reads, and must not find its queue destroyed.
std::atomic<Queue*> g_queue{nullptr};

void writer_loop(Queue* q) {
  std::unique_lock lock(q->m);
  for (;;) {
    q->wake.wait(lock, [q] { return !q->texts.empty(); });
    std::string text = std::move(q->texts.front());
    q->texts.pop_front();
    q->writing = true;
    lock.unlock();
    // Waits for room in poll() for as long as it takes (lines behind it queue, then drop);
    // a reader that is gone (EPIPE, SIGPIPE ignored) loses the text.
    const bool whole = write_waiting(STDERR_FILENO, text, /*stall_ms=*/-1, /*total_ms=*/-1);
    if (!whole) q->dropped.fetch_add(line_count(text), std::memory_order_relaxed);
    lock.lock();
    q->bytes -= text.size();
    q->writing = false;
    ++q->written;
    q->progress.notify_all();
  }
}

void emit(std::string text) {
  Queue* q = g_queue.load(std::memory_order_acquire);
  if (!q) {
    std::fputs(text.c_str(), stderr);  // one call: whole lines from each thread
    return;
  }
  {
    std::lock_guard lock(q->m);
    if (q->bytes + text.size() > kMaxQueuedBytes) {
      q->dropped.fetch_add(line_count(text), std::memory_order_relaxed);
      return;
    }
    q->bytes += text.size();
    q->texts.push_back(std::move(text));
  }
  q->wake.notify_one();
}
}  // namespace

void init(const char* program, int verbosity) {
  g_program = program;
  int l = static_cast<int>(Level::info);
  if (const char* env = std::getenv("FOVEAL_LOG"))
    for (int i = 0; i < 4; ++i)
      if (std::strcmp(env, kNames[i]) == 0) l = i;
  g_level = std::clamp(l + verbosity, 0, 3);
}

Level level() { return static_cast<Level>(g_level.load()); }
bool enabled(Level l) { return static_cast<int>(l) <= g_level.load(); }

void write(Level l, const std::string& msg) {
  if (!enabled(l)) return;
  emit(std::string(g_program) + ": " + kNames[static_cast<int>(l)] + ": " + msg + "\n");
}

void raw(const std::string& text) { emit(text); }

void start_writer_thread() {
  if (g_queue.load()) return;
  // Nothing stdio holds may go out through the old descriptions later.
  std::fflush(stdout);
  std::fflush(stderr);
  for (int fd : {STDOUT_FILENO, STDERR_FILENO})
    g_guard[fd].store(static_cast<int>(make_own_nonblocking(fd)), std::memory_order_relaxed);
  auto* q = new Queue;
  // The writer must never take a signal meant for the program's own handling.
  sigset_t all, old;
  sigfillset(&all);
  pthread_sigmask(SIG_BLOCK, &all, &old);
  std::thread(writer_loop, q).detach();
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  g_queue.store(q, std::memory_order_release);
}

std::uint64_t dropped_lines() {
  const Queue* q = g_queue.load(std::memory_order_acquire);
  return q ? q->dropped.load(std::memory_order_relaxed) : 0;
}

bool flush(int stall_ms) {
  Queue* q = g_queue.load(std::memory_order_acquire);
  if (!q) return true;
  const auto give_up = Clock::now() + std::chrono::milliseconds(2 * stall_ms);
  std::unique_lock lock(q->m);
  while (!q->texts.empty() || q->writing) {
    const std::uint64_t before = q->written;
    // Waits while the reader keeps up; gives up once nothing was written for stall_ms,
    // or after twice that in all (a reader that takes a byte now and then).
    const auto until = std::min(give_up, Clock::now() + std::chrono::milliseconds(stall_ms));
    if (!q->progress.wait_until(lock, until, [&] { return q->written != before; })) return false;
  }
  return true;
}

bool out(const std::string& text, int stall_ms) {
  if (!g_queue.load(std::memory_order_acquire)) {
    std::fputs(text.c_str(), stdout);
    return std::fflush(stdout) == 0;
  }
  return write_waiting(STDOUT_FILENO, text, stall_ms, 2 * stall_ms);
}

}  // namespace foveal::log

#include "foveal/tools/log.hpp"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <condition_variable>
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

/// The queue between the threads that log and the one that writes stderr.
struct Queue {
  std::mutex m;
  std::condition_variable wake, progress;
  std::deque<std::string> texts;
  std::size_t bytes = 0;           ///< queued, not yet written
  bool writing = false;            ///< the writer holds a text outside the queue
  std::uint64_t written = 0;       ///< texts written (or failed) so far: flush() sees progress
  std::atomic<std::uint64_t> dropped{0};
};
// Set once by start_writer_thread() and never freed: at exit the writer may still sit
// in write() on a pipe nobody reads, and must not find its queue destroyed.
std::atomic<Queue*> g_queue{nullptr};

void write_all(const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(STDERR_FILENO, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // EPIPE (SIGPIPE ignored), a closed descriptor: the text is lost
    done += static_cast<std::size_t>(n);
  }
}

void writer_loop(Queue* q) {
  std::unique_lock lock(q->m);
  for (;;) {
    q->wake.wait(lock, [q] { return !q->texts.empty(); });
    std::string text = std::move(q->texts.front());
    q->texts.pop_front();
    q->writing = true;
    lock.unlock();
    write_all(text);  // may block for ever: nobody else waits for it
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
      q->dropped.fetch_add(1, std::memory_order_relaxed);
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
  std::unique_lock lock(q->m);
  while (!q->texts.empty() || q->writing) {
    const std::uint64_t before = q->written;
    // Waits while the reader keeps up; gives up once nothing was written for stall_ms.
    if (!q->progress.wait_for(lock, std::chrono::milliseconds(stall_ms), [&] { return q->written != before; }))
      return false;
  }
  return true;
}

}  // namespace foveal::log

#include "foveal/runtime/gaze_loop.hpp"

#include <pthread.h>
#include <sched.h>

#include <algorithm>

namespace foveal {

namespace {
constexpr auto kPollTimeout = std::chrono::milliseconds(50);  // bounds stop() latency
constexpr TimeNs kStatsPeriod = 50 * kNsPerMs;
}  // namespace

GazeLoop::GazeLoop(GazeSource& source, Mapper mapper, Observer observer)
    : source_(source), mapper_(std::move(mapper)), observer_(std::move(observer)) {}

GazeLoop::~GazeLoop() { stop(); }

void GazeLoop::start(int rt_priority) {
  rt_priority_ = rt_priority;
  stop_ = false;
  finished_ = false;
  thread_ = std::thread([this] { run(); });
}

void GazeLoop::stop() {
  stop_.store(true, std::memory_order_release);
  if (thread_.joinable()) thread_.join();
}

GazeLoopStats GazeLoop::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

void GazeLoop::set_mapper(Mapper m) {
  std::lock_guard lock(mutex_);
  next_mapper_ = std::move(m);
  mapper_pending_.store(true, std::memory_order_release);
}

void GazeLoop::publish_stats(bool force) {
  const TimeNs now = monotonic_now_ns();
  if (!force && now - last_publish_ < kStatsPeriod) return;
  last_publish_ = now;
  local_.latency_p50_ns = latency_.percentile(0.5);
  local_.latency_p99_ns = latency_.percentile(0.99);
  local_.latency_max_ns = latency_.max();
  std::lock_guard lock(mutex_);
  stats_ = local_;
}

bool GazeLoop::reconnect() {
  // Device loss: keep the last fovea published, retry with backoff until it is back.
  TimeNs backoff = 50 * kNsPerMs;
  while (!stop_.load(std::memory_order_acquire)) {
    source_.close();
    if (source_.open() && source_.start()) {
      ++local_.reconnects;
      return true;
    }
    const TimeNs until = monotonic_now_ns() + backoff;
    while (!stop_.load(std::memory_order_acquire) && monotonic_now_ns() < until) sleep_until_ns(monotonic_now_ns() + 10 * kNsPerMs);
    backoff = std::min<TimeNs>(backoff * 2, 400 * kNsPerMs);  // resume within ~0.5 s of return
  }
  return false;
}

void GazeLoop::run() {
  if (rt_priority_ > 0) {
    // Pacing and latency depend on waking on time; a real-time class keeps other load
    // from delaying this thread. The thread sleeps between samples, so it cannot starve.
    sched_param sp{};
    sp.sched_priority = rt_priority_;
    local_.realtime = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp) == 0;
  }
  while (!stop_.load(std::memory_order_acquire)) {
    if (mapper_pending_.load(std::memory_order_acquire)) {
      std::lock_guard lock(mutex_);
      mapper_ = std::move(next_mapper_);
      mapper_pending_.store(false, std::memory_order_relaxed);
    }
    ReadResult r = source_.next(kPollTimeout);
    if (r.status == ReadStatus::sample) {
      const TimeNs arrival = monotonic_now_ns();
      if (paused_.load(std::memory_order_relaxed)) {
        ++local_.skipped;
      } else {
        const FoveaFrame f = mapper_(r.sample);
        latest_.store(f);
        latency_.add(monotonic_now_ns() - arrival);
        ++local_.samples;
        if (observer_) observer_(r.sample, f);
      }
    } else if (r.status == ReadStatus::timeout) {
      ++local_.timeouts;
    } else if (r.status == ReadStatus::end) {
      local_.ended = true;
      break;
    } else if (r.status == ReadStatus::disconnected) {
      ++local_.disconnects;
      if (!reconnect()) break;
    } else {
      local_.failed = true;
      local_.last_error = r.error.message;
      break;
    }
    publish_stats(false);
  }
  publish_stats(true);
  finished_.store(true, std::memory_order_release);
}

}  // namespace foveal

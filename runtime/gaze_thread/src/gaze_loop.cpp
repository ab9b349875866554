#include "foveal/runtime/gaze_loop.hpp"

#include <pthread.h>
#include <sched.h>

#include <algorithm>

namespace foveal {

namespace {
constexpr auto kPollTimeout = std::chrono::milliseconds(50);  // bounds stop() latency
constexpr TimeNs kStatsPeriod = 50 * kNsPerMs;
}  // namespace

const char* source_state_name(SourceState s) {
  switch (s) {
    case SourceState::waiting: return "waiting";
    case SourceState::streaming: return "streaming";
    case SourceState::reconnecting: return "reconnecting";
    case SourceState::ended: return "ended";
    case SourceState::failed: return "failed";
    case SourceState::stopped: return "stopped";
  }
  return "?";
}

GazeLoop::GazeLoop(GazeSource& source, Mapper mapper, Observer observer, bool wait_for_source)
    : source_(source), mapper_(std::move(mapper)), observer_(std::move(observer)), wait_for_source_(wait_for_source) {}

GazeLoop::~GazeLoop() { stop(); }

void GazeLoop::set_no_gaze(const FoveaFrame& f) {
  no_gaze_ = f;
  latest_.store(f);
}

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
  // Device loss: no gaze until it is back (the centre, when set_no_gaze() said what that
  // is; else the last fovea stays); retry with backoff.
  if (no_gaze_) latest_.store(*no_gaze_);
  local_.state = SourceState::reconnecting;
  publish_stats(true);
  if (!reopen_with_backoff(source_, [this] { return stop_.load(std::memory_order_acquire); })) return false;
  ++local_.reconnects;
  local_.state = SourceState::streaming;
  local_.device = source_.info();
  return true;
}

void GazeLoop::run() {
  if (rt_priority_ > 0) {
    // Pacing and latency depend on waking on time; a real-time class keeps other load
    // from delaying this thread. The thread sleeps between samples, so it cannot starve.
    sched_param sp{};
    sp.sched_priority = rt_priority_;
    local_.realtime = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp) == 0;
  }
  if (wait_for_source_) {
    // A live device that is not there yet: wait for it the way a lost one is waited for,
    // saying why in the stats.
    local_.state = SourceState::waiting;
    Status first = source_.open();
    if (first) first = source_.start();
    if (!first) {
      local_.waiting_for = first.error().message;
      publish_stats(true);
      if (!reopen_with_backoff(source_, [this] { return stop_.load(std::memory_order_acquire); })) {
        local_.state = SourceState::stopped;
        publish_stats(true);
        finished_.store(true, std::memory_order_release);
        return;
      }
    }
    local_.waiting_for.clear();
  }
  local_.state = SourceState::streaming;
  local_.device = source_.info();
  publish_stats(true);
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
        FoveaFrame f = mapper_(r.sample);
        f.device_t_ns = r.device_t_ns;
        f.arrival_ns = arrival;
        latest_.store(f);
        latency_.add(monotonic_now_ns() - arrival);
        ++local_.samples;
        if (observer_) observer_(r.sample, f);
      }
    } else if (r.status == ReadStatus::timeout) {
      ++local_.timeouts;
    } else if (r.status == ReadStatus::end) {
      local_.ended = true;
      local_.state = SourceState::ended;
      break;
    } else if (r.status == ReadStatus::disconnected) {
      ++local_.disconnects;
      if (!reconnect()) break;
    } else {
      local_.failed = true;
      local_.state = SourceState::failed;
      local_.last_error = r.error.message;
      break;
    }
    publish_stats(false);
  }
  if (local_.state == SourceState::streaming || local_.state == SourceState::reconnecting) local_.state = SourceState::stopped;
  publish_stats(true);
  finished_.store(true, std::memory_order_release);
}

}  // namespace foveal

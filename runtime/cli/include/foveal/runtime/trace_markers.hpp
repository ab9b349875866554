#pragma once
// Event markers for the fovea trace (`foveal ctl mark TEXT`, docs/daemon.md): the
// control thread stamps and queues them, the gaze thread writes each one into the trace
// before the first sample row that is later than it, so the trace stays in time order.
#include <atomic>
#include <cstdint>
#include <mutex>
#include <vector>

#include "foveal/core/gaze_marker.hpp"

namespace foveal::cli {

/// Stamped on CLOCK_MONOTONIC, the clock of the samples.
using TraceMarker = GazeMarker;

class MarkerQueue {
 public:
  /// Markers that may wait for the gaze thread (paused, or no device yet): a client
  /// that floods marks is refused past this rather than growing the daemon's memory.
  static constexpr std::size_t kMaxWaiting = 10'000;

  /// Any thread. False (and nothing queued) when kMaxWaiting markers wait already.
  bool push(TraceMarker m) {
    std::lock_guard lock(mutex_);
    if (queue_.size() >= kMaxWaiting) return false;
    queue_.push_back(std::move(m));
    waiting_.store(queue_.size(), std::memory_order_release);
    ++pushed_;
    return true;
  }
  /// The markers stamped at or before t_ns, oldest first. Costs one atomic load when none wait.
  std::vector<TraceMarker> take_until(TimeNs t_ns) {
    std::vector<TraceMarker> out;
    if (waiting_.load(std::memory_order_acquire) == 0) return out;
    std::lock_guard lock(mutex_);
    std::size_t n = 0;
    while (n < queue_.size() && queue_[n].t_ns <= t_ns) ++n;
    out.assign(std::make_move_iterator(queue_.begin()), std::make_move_iterator(queue_.begin() + static_cast<std::ptrdiff_t>(n)));
    queue_.erase(queue_.begin(), queue_.begin() + static_cast<std::ptrdiff_t>(n));
    waiting_.store(queue_.size(), std::memory_order_release);
    return out;
  }
  std::vector<TraceMarker> take_all() { return take_until(INT64_MAX); }
  std::uint64_t pushed() const { return pushed_.load(); }

 private:
  std::mutex mutex_;
  std::vector<TraceMarker> queue_;  // in stamp order: one clock, stamped under the lock
  std::atomic<std::size_t> waiting_{0};
  std::atomic<std::uint64_t> pushed_{0};
};

}  // namespace foveal::cli

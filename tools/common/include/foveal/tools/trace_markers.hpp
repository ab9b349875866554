#pragma once
// Event markers for the fovea trace (`foveal ctl mark TEXT`, docs/daemon.md): the
// control thread stamps and queues them, the gaze thread writes each one into the trace
// before the first sample row that is later than it, so the trace stays in time order.
#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "foveal/core/clock.hpp"
#include "foveal/core/error.hpp"

namespace foveal::cli {

struct TraceMarker {
  TimeNs t_ns = 0;  ///< CLOCK_MONOTONIC, the clock of the samples
  std::string text;
};

constexpr std::size_t kMaxMarkerBytes = 256;

/// A marker's text: 1 to kMaxMarkerBytes bytes, no control characters (it is the rest of
/// a CSV row, so commas are fine and line ends are not).
inline Status check_marker_text(std::string_view text) {
  if (text.empty()) return bad_input("mark: the text is empty");
  if (text.size() > kMaxMarkerBytes)
    return bad_input("mark: the text has " + std::to_string(text.size()) + " bytes; at most " +
                     std::to_string(kMaxMarkerBytes));
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f)
      return bad_input("mark: byte " + std::to_string(i + 1) + " of the text is a control character");
  }
  return {};
}

class MarkerQueue {
 public:
  /// Any thread.
  void push(TraceMarker m) {
    std::lock_guard lock(mutex_);
    queue_.push_back(std::move(m));
    waiting_.store(queue_.size(), std::memory_order_release);
    ++pushed_;
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

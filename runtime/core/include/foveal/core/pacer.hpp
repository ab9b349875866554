#pragma once
// Paces a stream recorded on its own time base onto the runtime clock at a speed factor.
#include <chrono>
#include <cmath>
#include <limits>

#include "foveal/core/clock.hpp"

namespace foveal {

class Pacer {
 public:
  /// speed 1 = real time, 2 = twice as fast, 0 = as fast as possible.
  explicit Pacer(double speed = 1.0) : speed_(speed) {}
  /// Anchors stream time `stream_t0` to the runtime clock now.
  void start(TimeNs stream_t0) {
    stream_t0_ = stream_t0;
    runtime_t0_ = monotonic_now_ns();
  }
  /// Runtime-clock time at which the item stamped `stream_t` is due.
  /// Saturates instead of wrapping: a crafted log's span, slowed down, can pass int64.
  TimeNs due(TimeNs stream_t) const {
    constexpr TimeNs kMax = std::numeric_limits<TimeNs>::max(), kMin = std::numeric_limits<TimeNs>::min();
    TimeNs rel = 0;
    if (__builtin_sub_overflow(stream_t, stream_t0_, &rel)) return stream_t > stream_t0_ ? kMax : kMin;
    if (speed_ > 0.0) {  // else timestamps keep their spacing
      const double scaled = static_cast<double>(rel) / speed_;
      if (!(std::fabs(scaled) < 0x1p62)) return scaled > 0 ? kMax : kMin;
      rel = static_cast<TimeNs>(scaled);
    }
    TimeNs t = 0;
    if (__builtin_add_overflow(runtime_t0_, rel, &t)) return rel > 0 ? kMax : kMin;
    return t;
  }
  /// Sleeps until `due`, but never longer than `timeout`; true if `due` was reached.
  bool wait(TimeNs due_t, std::chrono::nanoseconds timeout) const {
    if (speed_ <= 0.0) return true;
    const TimeNs now = monotonic_now_ns();
    if (due_t <= now) return true;
    if (due_t - now > timeout.count()) {
      sleep_until_ns(now + timeout.count());
      return false;
    }
    sleep_until_ns(due_t);
    return true;
  }
  double speed() const { return speed_; }

 private:
  double speed_;
  TimeNs stream_t0_ = 0;
  TimeNs runtime_t0_ = 0;
};

}  // namespace foveal

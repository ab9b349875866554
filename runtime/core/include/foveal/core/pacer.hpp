#pragma once
// Paces a stream recorded on its own time base onto the runtime clock at a speed factor.
#include <chrono>

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
  TimeNs due(TimeNs stream_t) const {
    const TimeNs rel = stream_t - stream_t0_;
    if (speed_ <= 0.0) return runtime_t0_ + rel;  // timestamps keep their spacing
    return runtime_t0_ + static_cast<TimeNs>(static_cast<double>(rel) / speed_);
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

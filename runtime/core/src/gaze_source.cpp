#include "foveal/core/gaze_source.hpp"

#include <algorithm>

#include "foveal/core/clock.hpp"

namespace foveal {

bool reopen_with_backoff(GazeSource& source, const std::function<bool()>& should_stop) {
  TimeNs backoff = 50 * kNsPerMs;
  while (!should_stop()) {
    source.close();
    if (source.open() && source.start()) return true;
    // Sleep in short steps so that a stop request is seen within 10 ms.
    const TimeNs until = monotonic_now_ns() + backoff;
    while (!should_stop() && monotonic_now_ns() < until) sleep_until_ns(std::min(until, monotonic_now_ns() + 10 * kNsPerMs));
    backoff = std::min<TimeNs>(backoff * 2, 400 * kNsPerMs);
  }
  return false;
}

}  // namespace foveal

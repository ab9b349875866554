#include "foveal/core/gaze_source.hpp"

#include <algorithm>

#include "foveal/core/clock.hpp"
#include "foveal/core/pose_device.hpp"

namespace foveal {

bool reopen_with_backoff(GazeSource& source, const std::function<bool()>& should_stop) {
  return retry_with_backoff(
      [&source] {
        source.close();
        return source.open() && source.start();
      },
      should_stop);
}

bool reopen_with_backoff(PoseDevice& device, const std::function<bool()>& should_stop) {
  return retry_with_backoff(
      [&device] {
        device.close();
        return device.open() && device.start();
      },
      should_stop);
}

bool retry_with_backoff(const std::function<bool()>& attempt, const std::function<bool()>& should_stop) {
  TimeNs backoff = 50 * kNsPerMs;
  while (!should_stop()) {
    if (attempt()) return true;
    // Sleep in short steps so that a stop request is seen within 10 ms.
    const TimeNs until = monotonic_now_ns() + backoff;
    while (!should_stop() && monotonic_now_ns() < until) sleep_until_ns(std::min(until, monotonic_now_ns() + 10 * kNsPerMs));
    backoff = std::min<TimeNs>(backoff * 2, 400 * kNsPerMs);
  }
  return false;
}

}  // namespace foveal

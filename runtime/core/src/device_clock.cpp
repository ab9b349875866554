#include "foveal/core/device_clock.hpp"

namespace foveal {

TimeNs DeviceClock::map(TimeNs arrival_ns, std::optional<std::int64_t> device_ns) {
  TimeNs t = arrival_ns;
  if (device_ns) {
    const std::int64_t offset = arrival_ns - *device_ns;
    if (!anchored_ || *device_ns <= last_device_) {
      offset_ = offset;  // first report, or the device clock restarted
      anchored_ = true;
    } else if (offset < offset_) {
      offset_ = offset;  // a less-delayed report: tighter bound
    }
    last_device_ = *device_ns;
    // t <= arrival by construction; an overflowing sum means a garbage device time.
    if (__builtin_add_overflow(*device_ns, offset_, &t) || arrival_ns - t > kMaxLagNs) {  // the device clock runs slow: follow the arrivals
      offset_ = offset;
      t = arrival_ns;
    }
  }
  if (t <= last_out_) t = last_out_ + 1;
  last_out_ = t;
  return t;
}

}  // namespace foveal

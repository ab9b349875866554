#pragma once
// Maps a device's own timestamps onto the runtime clock, so that reports read in a
// burst keep their real spacing: t = device_time + offset, where offset is the
// smallest (arrival - device_time) seen (the least-delayed report). Delivered times
// always increase; a device clock that jumps back or drifts away re-anchors the offset.
#include <cstdint>
#include <optional>

#include "foveal/core/clock.hpp"

namespace foveal {

class DeviceClock {
 public:
  /// Re-anchor when a mapped time would lag its arrival by more than this.
  static constexpr TimeNs kMaxLagNs = 50'000'000;

  /// The runtime time of a report that arrived at `arrival_ns` carrying `device_ns`
  /// (nullopt: the device gave no timestamp, the arrival time is used).
  TimeNs map(TimeNs arrival_ns, std::optional<std::int64_t> device_ns);
  /// A device time of the same clock on the runtime clock with the current offset,
  /// without updating it (a second stream of the same device, e.g. poses beside IMU
  /// samples). The device time itself when nothing is anchored yet.
  TimeNs to_runtime(std::int64_t device_ns) const { return device_ns + offset_; }
  bool anchored() const { return anchored_; }
  void reset() { *this = DeviceClock{}; }

 private:
  bool anchored_ = false;
  std::int64_t offset_ = 0;
  std::int64_t last_device_ = 0;
  TimeNs last_out_ = 0;
};

}  // namespace foveal

#pragma once
// The one interface every gaze driver implements (replay, synthetic, hid, usb).
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

#include "foveal/core/error.hpp"
#include "foveal/core/gaze_sample.hpp"

namespace foveal {

struct SourceInfo {
  std::string driver;         ///< "replay", "synthetic", "hid", "usb"
  std::string name;           ///< human-readable device or file name
  std::string path;           ///< device node or file path, "" if none
  double nominal_rate_hz = 0; ///< what the device/log claims
  std::uint16_t vendor_id = 0;
  std::uint16_t product_id = 0;
  /// The samples carry head poses (GazeSample::head): a replayed v2 log, later an HMD
  /// driver. Their times are the samples' (the runtime clock, re-based like the gaze).
  bool head_pose = false;
};

/// What next() produced. Not an error channel for device data: malformed reports are
/// counted by the driver and skipped, never delivered.
enum class ReadStatus {
  sample,        ///< `sample` holds a new sample
  timeout,       ///< nothing within the timeout; try again
  end,           ///< a finite source is exhausted (replay without loop)
  disconnected,  ///< the device went away; the caller may reopen() later
  error,         ///< unrecoverable; `error` says why
};

struct ReadResult {
  ReadStatus status = ReadStatus::timeout;
  GazeSample sample{};
  /// `sample`'s time on the tracker's own clock, before it was mapped to the runtime's
  /// (a replay: the log row's t_ns); 0 when the driver has none. frames.csv names the
  /// sample a frame used by it (docs/latency.md).
  TimeNs device_t_ns = 0;
  Error error{};
};

/// Lifecycle: open() -> start() -> next()* -> stop() -> close(). Implementations are
/// used from one thread at a time; none of the calls throws.
class GazeSource {
 public:
  virtual ~GazeSource() = default;
  virtual Status open() = 0;
  virtual void close() = 0;
  virtual Status start() = 0;
  virtual void stop() = 0;
  /// Blocks at most `timeout` for the next sample. Timestamps are on the runtime clock.
  virtual ReadResult next(std::chrono::nanoseconds timeout) = 0;
  virtual SourceInfo info() const = 0;
};

/// Device loss: closes `source` and tries open() + start() again with backoff (50 ms
/// doubling to 400 ms, so a device that is back is read again within about 0.5 s) until
/// it works (true) or `should_stop` says so (false). Every driver's recovery goes
/// through here: the gaze loop's, `foveal record`'s.
bool reopen_with_backoff(GazeSource& source, const std::function<bool()>& should_stop);

/// The backoff loop itself: calls `attempt` (50 ms doubling to 400 ms between tries)
/// until it returns true (true) or `should_stop` says so (false). Pose devices share it.
bool retry_with_backoff(const std::function<bool()>& attempt, const std::function<bool()>& should_stop);

}  // namespace foveal

#pragma once
// The driver for HUTRR74 eye trackers (usage page 0x12) through hidapi: finds the
// tracker by its report descriptor, reads its Capabilities, Configuration and Tracker
// Status feature reports, enables gaze with a Mode Request and turns Tracking Data
// input reports into GazeSamples (docs/hid.md). Malformed device data is counted and
// logged, never delivered; a vanished device reads as ReadStatus::disconnected.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "foveal/core/gaze_source.hpp"
#include "foveal/core/problem_throttle.hpp"
#include "foveal/drivers/hid/device_clock.hpp"
#include "foveal/drivers/hid/hid_backend.hpp"
#include "foveal/drivers/hid/screen_gaze.hpp"
#include "foveal/drivers/hid/tracker_discovery.hpp"
#include "foveal/drivers/hid/tracker_reports.hpp"

namespace foveal::hid {

struct HidTrackerOptions {
  std::string device;  ///< a hidraw path; "" = the first eye tracker found
  std::uint8_t mode = kModeGazePoint | kModeEyePosition;
  double ipd_mm = 63;  ///< nominal IPD when the tracker reports no eye positions
  /// Where problems are logged (rate-limited); default: stderr.
  std::function<void(const std::string&)> log;
};

/// What the driver saw; survives reopen() so the totals cover a whole session.
struct HidTrackerCounters {
  std::uint64_t reports = 0;          ///< input reports read
  std::uint64_t samples = 0;          ///< samples delivered
  std::uint64_t invalid_gaze = 0;     ///< well-formed reports without a valid gaze point
  std::uint64_t malformed = 0;        ///< reports that failed to decode (truncated included)
  std::uint64_t truncated = 0;
  std::uint64_t unknown_reports = 0;  ///< report IDs the descriptor does not have as input
  std::uint64_t status_reports = 0;
  std::uint64_t feature_errors = 0;   ///< feature reports that could not be read or decoded
  std::uint64_t opens = 0;
  std::uint64_t disconnects = 0;
  std::string last_problem;
};

class HidTrackerSource final : public GazeSource {
 public:
  explicit HidTrackerSource(HidTrackerOptions opts, std::shared_ptr<HidBackend> backend = make_hidapi_backend());
  ~HidTrackerSource() override;

  Status open() override;
  void close() override;
  Status start() override;
  void stop() override;
  ReadResult next(std::chrono::nanoseconds timeout) override;
  SourceInfo info() const override;

  const HidTrackerCounters& counters() const { return counters_; }
  /// After open(): if the Tracker Status feature report gave no sampling frequency,
  /// listens up to `timeout` for a Tracker Status input report. True if the rate is known.
  bool wait_for_rate(std::chrono::nanoseconds timeout);

  const TrackerStatus& status() const { return status_; }
  const TrackerCapabilities& capabilities() const { return caps_; }
  const TrackerConfiguration& configuration() const { return config_; }
  const ScreenPlane& screen() const { return plane_; }
  /// The last decoded Tracking Data (for tests and tools that want the raw values).
  const TrackingData& last_tracking() const { return last_; }

 private:
  Result<TrackerEntry> choose_device(HidBackend& backend);
  void read_features();
  void problem(std::string message);
  /// Handles one input report; true if it produced `out`.
  bool handle_report(std::span<const std::uint8_t> report, TimeNs arrival, GazeSample& out);

  HidTrackerOptions opts_;
  std::shared_ptr<HidBackend> backend_;
  std::unique_ptr<HidDevice> device_;
  std::optional<TrackerEntry> entry_;  ///< the device opened last (kept for reconnection)
  bool started_ = false;
  TrackerStatus status_;
  TrackerCapabilities caps_;
  TrackerConfiguration config_;
  ScreenPlane plane_;
  TrackingData last_;
  TimeNs last_device_t_ns_ = 0;  ///< the last delivered report's device time
  DeviceClock clock_;
  HidTrackerCounters counters_;
  ProblemThrottle problems_;
  std::vector<std::uint8_t> buffer_;
};

}  // namespace foveal::hid

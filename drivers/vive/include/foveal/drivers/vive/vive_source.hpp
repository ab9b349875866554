#pragma once
// The Vive / Vive Pro as a PoseDevice: the IMU input reports of its Valve sensor device
// (3DoF: the runtime fuses them, runtime/head), and at every open() the IMU ranges and
// the configuration (IMU calibration, lens data). Untested against a headset (none
// here): the parsers are unit-tested on synthesised reports, the whole driver runs
// against an emulated device in the VM suite.
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "foveal/core/device_clock.hpp"
#include "foveal/core/pose_device.hpp"
#include "foveal/core/problem_throttle.hpp"
#include "foveal/drivers/hid/hid_backend.hpp"
#include "foveal/drivers/vive/vive_config.hpp"

namespace foveal::vive {

struct ViveOptions {
  std::string device;  ///< hidraw path; empty: the first Vive sensor device found at each open()
  std::function<void(const std::string&)> log;  ///< default: stderr, rate-limited
};

struct ViveCounters {
  std::uint64_t reports = 0, samples = 0, malformed = 0, other_reports = 0, opens = 0, disconnects = 0;
  std::uint64_t config_errors = 0;  ///< opens whose configuration could not be read
  std::string last_problem;
};

/// A Vive sensor device present.
struct ViveDeviceEntry {
  std::string path, name, serial;
  std::uint16_t vendor_id = 0, product_id = 0;
};
Result<std::vector<ViveDeviceEntry>> find_vive_devices(hid::HidBackend& backend);

/// Reads the configuration JSON through feature reports 0x10 / 0x11.
Result<std::string> read_config_json(hid::HidDevice& dev);

class ViveSource final : public PoseDevice {
 public:
  explicit ViveSource(ViveOptions opts = {}, std::shared_ptr<hid::HidBackend> backend = nullptr);
  Status open() override;
  void close() override;
  Status start() override;
  void stop() override {}
  PoseReading next(std::chrono::nanoseconds timeout) override;
  PoseDeviceInfo info() const override;

  /// The configuration read at the last successful open() (nullopt: none could be).
  const std::optional<Config>& config() const { return config_; }
  const std::string& config_json() const { return config_json_; }
  const ViveCounters& counters() const { return counters_; }

 private:
  void problem(std::string message);

  ViveOptions opts_;
  std::shared_ptr<hid::HidBackend> backend_;
  std::unique_ptr<hid::HidDevice> dev_;
  ViveDeviceEntry entry_;
  std::optional<Config> config_;
  Config calibration_;  ///< config_ or the defaults
  std::string config_json_;
  ImuRange range_;
  std::optional<std::uint8_t> last_seq_;
  std::int64_t ticks_high_ = 0;  ///< unwraps the 32-bit tick counter
  std::optional<std::uint32_t> last_ticks_;
  DeviceClock clock_;
  std::deque<ImuSample> queue_;
  ViveCounters counters_;
  ProblemThrottle problems_;
};

}  // namespace foveal::vive

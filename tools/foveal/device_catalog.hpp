#pragma once
// The trackers `foveal devices` lists and `foveal record` opens: HID eye trackers
// (usage page 0x12) first, then PlayStation VR2 headsets when the USB driver is built.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/core/gaze_source.hpp"

namespace foveal::cmd {

struct DeviceRow {
  std::size_t id = 0;
  std::string driver, path, vid_pid, name, serial, problem;
  double rate_hz = 0;  ///< 0: unknown
};

/// Every tracker present. With `probe_rate`, HID trackers are opened to read their rate.
Result<std::vector<DeviceRow>> list_devices(bool probe_rate);

struct OpenedDevice {
  std::unique_ptr<GazeSource> source;
  std::function<nlohmann::json()> counters;  ///< the driver's counters, for summaries
};

/// A source for `id`: "" or "auto" (the first tracker), an id from list_devices, a
/// hidraw path, or "psvr2". Not opened yet.
Result<OpenedDevice> make_device_source(const std::string& id);

}  // namespace foveal::cmd

#pragma once
// One row of the driver list: how a spec's driver lists its devices and makes sources.
#include <functional>
#include <string>
#include <vector>

#include "foveal/drivers/probe.hpp"

namespace foveal::probe {

struct DriverEntry {
  const char* name;   ///< the spec's driver word
  const char* usage;  ///< e.g. "hid[:ID|PATH]"
  const char* what;   ///< one line for --help
  enum class Arg { none, optional, required } arg = Arg::none;
  bool live = false;  ///< a device tracker: listed by `foveal devices`, tried by `auto`
  /// Live drivers: the devices present (probe_rate: open them to read the rate).
  std::function<Result<std::vector<DeviceRow>>(bool probe_rate)> list;
  std::function<Result<OpenedSource>(const std::string& arg, const SourceOptions&)> make;
};

/// One head-pose driver: how it lists its headsets and makes pose devices.
struct PoseDriverEntry {
  const char* name;
  const char* usage;
  const char* what;
  std::function<Result<std::vector<HmdRow>>()> list;
  std::function<Result<OpenedPoseDevice>(const std::string& arg, const SourceOptions&)> make;
};

/// Every pose driver of this build, in the order `auto` tries them.
const std::vector<PoseDriverEntry>& pose_driver_list();
PoseDriverEntry psvr2_pose_entry();
PoseDriverEntry vive_pose_entry();

/// Every driver of this build, live trackers in the order `auto` tries them.
const std::vector<DriverEntry>& driver_list();

/// The drivers foveal has that this build left out (e.g. "psvr2" without libusb).
const std::vector<std::string>& drivers_left_out();

DriverEntry replay_entry();
DriverEntry synthetic_entry();
DriverEntry hid_entry();
DriverEntry psvr2_entry();

std::string hex4(std::uint16_t v);

}  // namespace foveal::probe

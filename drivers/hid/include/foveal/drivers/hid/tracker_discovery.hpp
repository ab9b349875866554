#pragma once
// Finds HUTRR74 eye trackers among all HID devices by parsing each report descriptor.
#include <string>
#include <vector>

#include "foveal/drivers/hid/hid_backend.hpp"
#include "foveal/drivers/hid/tracker_layout.hpp"

namespace foveal::hid {

struct TrackerEntry {
  HidDeviceEntry device;
  TrackerLayout layout;
};

/// Every device whose descriptor has an Eye Tracker application collection, in the
/// backend's order. Devices with unreadable or malformed descriptors are skipped.
Result<std::vector<TrackerEntry>> find_eye_trackers(HidBackend& backend);

}  // namespace foveal::hid

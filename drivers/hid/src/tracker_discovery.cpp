#include "foveal/drivers/hid/tracker_discovery.hpp"

namespace foveal::hid {

Result<std::vector<TrackerEntry>> find_eye_trackers(HidBackend& backend) {
  auto devices = backend.enumerate();
  if (!devices) return devices.error();
  std::vector<TrackerEntry> out;
  for (HidDeviceEntry& d : *devices) {
    if (d.descriptor.empty()) continue;
    auto parsed = parse_report_descriptor(d.descriptor);
    if (!parsed || !is_eye_tracker(*parsed)) continue;
    auto layout = make_tracker_layout(std::move(parsed.value()));
    if (!layout) continue;  // an eye tracker we cannot drive (no gaze report or no mode request)
    out.push_back({std::move(d), std::move(layout.value())});
  }
  return out;
}

}  // namespace foveal::hid

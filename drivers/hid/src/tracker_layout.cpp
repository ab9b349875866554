#include "foveal/drivers/hid/tracker_layout.hpp"

#include <algorithm>

namespace foveal::hid {
namespace {

bool in_collection(const ReportDescriptor& d, const Field& f, std::uint16_t usage) {
  const auto path = d.collection_path(f);
  return std::find(path.begin(), path.end(), make_usage(kEyeTrackerPage, usage)) != path.end();
}

/// The first report of `type` with a field inside the logical collection `usage`.
ReportRef find_ref(const ReportDescriptor& d, ReportType type, std::uint16_t usage) {
  ReportRef ref;
  for (const Field& f : d.fields) {
    if (f.type != type || !in_collection(d, f, usage)) continue;
    const ReportInfo* info = d.find_report(type, f.report_id);
    if (info == nullptr) continue;
    ref.present = true;
    ref.id = f.report_id;
    ref.bytes = info->bytes(d.uses_report_ids);
    return ref;
  }
  return ref;
}

bool has_field(const ReportDescriptor& d, ReportType type, std::uint8_t id, std::uint16_t usage) {
  for (const Field& f : d.fields) {
    if (f.type != type || f.report_id != id) continue;
    for (std::uint32_t i = 0; i < f.count; ++i)
      if (f.usage_of(i) == make_usage(kEyeTrackerPage, usage)) return true;
  }
  return false;
}

}  // namespace

bool is_eye_tracker(const ReportDescriptor& d) { return d.has_application(make_usage(kEyeTrackerPage, eye::kEyeTracker)); }

Result<TrackerLayout> make_tracker_layout(ReportDescriptor d) {
  if (!is_eye_tracker(d)) return bad_input("hid tracker: no Eye Tracker application collection (usage page 0x12, usage 0x01)");
  TrackerLayout l;
  l.tracking = find_ref(d, ReportType::input, eye::kTrackingData);
  l.capabilities = find_ref(d, ReportType::feature, eye::kCapabilities);
  l.configuration = find_ref(d, ReportType::feature, eye::kConfiguration);
  l.status_feature = find_ref(d, ReportType::feature, eye::kTrackerStatus);
  l.status_input = find_ref(d, ReportType::input, eye::kTrackerStatus);
  l.control = find_ref(d, ReportType::feature, eye::kTrackerControl);
  if (!l.tracking.present) return bad_input("hid tracker: the descriptor has no Tracking Data (0x12:0x10) input report");
  if (!has_field(d, ReportType::input, l.tracking.id, eye::kPositionX))
    return bad_input("hid tracker: Tracking Data report " + std::to_string(l.tracking.id) + " has no gaze Position X field");
  if (!l.control.present || !has_field(d, ReportType::feature, l.control.id, eye::kModeRequest))
    return bad_input("hid tracker: the descriptor has no Tracker Control feature report with a Mode Request (0x12:0x0400)");
  l.descriptor = std::move(d);
  return l;
}

Result<TrackerLayout> make_tracker_layout(std::span<const std::uint8_t> descriptor_bytes) {
  auto d = parse_report_descriptor(descriptor_bytes);
  if (!d) return d.error();
  return make_tracker_layout(std::move(d.value()));
}

}  // namespace foveal::hid

#include "foveal/drivers/hid/tracker_reports.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "foveal/drivers/hid/report_decoder.hpp"

namespace foveal::hid {
namespace {

constexpr Usage eye_usage(std::uint16_t id) { return make_usage(kEyeTrackerPage, id); }

/// The usage of the collection a field sits in directly (Gaze Location, Left Eye, ...).
Usage owner(const ReportDescriptor& d, const Field& f) {
  return f.collection >= 0 && f.collection < static_cast<int>(d.collections.size())
             ? d.collections[static_cast<std::size_t>(f.collection)].usage
             : 0;
}

/// A length in mm. HUTRR74 lengths are micrometres: cm with exponent -4 on real devices;
/// a field without a unit is taken as micrometres.
double length_mm(const DecodedValue& v) {
  const std::string unit = unit_name(v.field->unit);
  if (unit == "cm") return v.value * 10.0;
  if (unit == "in") return v.value * 25.4;
  return static_cast<double>(v.raw) / 1000.0;
}

Result<std::vector<DecodedValue>> decode_as(const TrackerLayout& l, ReportType type, const ReportRef& ref,
                                            std::span<const std::uint8_t> report, const char* what) {
  if (!ref.present) return bad_input(std::string("hid tracker: the descriptor has no ") + what + " report");
  if (l.descriptor.uses_report_ids && (report.empty() || report[0] != ref.id))
    return bad_input(std::string("hid tracker: ") + what + " report: expected report ID " + std::to_string(ref.id) +
                     ", got " + (report.empty() ? std::string("an empty report") : std::to_string(report[0])));
  auto values = decode_report(l.descriptor, type, report);
  if (!values) return Error{values.error().kind, std::string("hid tracker: ") + what + ": " + values.error().message};
  return values;
}

/// Timestamp in ns from the Timestamp value: one wide field, or a run of bytes joined by
/// join_multi_byte_values (little-endian, as the reference descriptor declares it).
/// nullopt if it would overflow (a run above 2^63 - 1 included); a single wide field's
/// logical range is not checked.
std::optional<std::int64_t> timestamp_ns(const ReportValue& stamp) {
  if ((stamp.is_run() && !stamp.in_range) || stamp.raw < 0) return std::nullopt;
  std::uint64_t raw = static_cast<std::uint64_t>(stamp.raw);
  const Field& f = *stamp.first->field;
  // Seconds × 10^exponent; without a time unit HUTRR74 says microseconds.
  int exponent = unit_name(f.unit) == "s" ? f.unit_exponent + 9 : 3;
  std::uint64_t factor = 1, divisor = 1;
  for (; exponent > 0; --exponent) factor *= 10;
  for (; exponent < 0; ++exponent) divisor *= 10;
  raw /= divisor;
  if (raw > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()) / factor) return std::nullopt;
  return static_cast<std::int64_t>(raw * factor);
}

struct Vec3Parts {
  const DecodedValue* x = nullptr;
  const DecodedValue* y = nullptr;
  const DecodedValue* z = nullptr;
  void take(const DecodedValue& v) {
    if (v.usage == eye_usage(eye::kPositionX)) x = &v;
    else if (v.usage == eye_usage(eye::kPositionY)) y = &v;
    else if (v.usage == eye_usage(eye::kPositionZ)) z = &v;
  }
};

/// An eye position is valid when complete, in range and in front of the screen (a
/// tracker that does not report eye positions leaves them 0).
bool eye_position(const Vec3Parts& p, glm::dvec3& out) {
  if (!p.x || !p.y || !p.z || !p.x->in_range || !p.y->in_range || !p.z->in_range) return false;
  out = {length_mm(*p.x), length_mm(*p.y), length_mm(*p.z)};
  return out.z > 0;
}

void insert_bits(std::vector<std::uint8_t>& data, std::uint32_t bit_offset, std::uint32_t bits, std::uint32_t value) {
  for (std::uint32_t b = 0; b < bits; ++b) {
    const std::uint32_t pos = bit_offset + b;
    const auto mask = static_cast<std::uint8_t>(1u << (pos % 8));
    if ((value >> b) & 1u) data[pos / 8] = static_cast<std::uint8_t>(data[pos / 8] | mask);
    else data[pos / 8] = static_cast<std::uint8_t>(data[pos / 8] & ~mask);
  }
}

}  // namespace

const char* configuration_status_name(int status) {
  switch (status) {
    case 1: return "ready";
    case 2: return "configuring";
    case 3: return "screen setup needed";
    case 4: return "user calibration needed";
    default: return "unknown";
  }
}

Result<TrackingData> decode_tracking_data(const TrackerLayout& l, std::span<const std::uint8_t> report) {
  auto values = decode_as(l, ReportType::input, l.tracking, report, "Tracking Data");
  if (!values) return values.error();
  TrackingData t;
  Vec3Parts gaze, left, right;
  for (const ReportValue& r : join_multi_byte_values(*values)) {
    const DecodedValue& v = *r.first;
    if (v.usage == eye_usage(eye::kTimestamp)) {
      if (!t.device_time_ns) t.device_time_ns = timestamp_ns(r);
      continue;
    }
    const Usage in = owner(l.descriptor, *v.field);
    if (in == eye_usage(eye::kGazeLocation)) gaze.take(v);
    else if (in == eye_usage(eye::kLeftEyePosition)) left.take(v);
    else if (in == eye_usage(eye::kRightEyePosition)) right.take(v);
  }
  if (gaze.x && gaze.y && gaze.x->in_range && gaze.y->in_range) {
    t.gaze_valid = true;
    t.gaze_x_mm = length_mm(*gaze.x);
    t.gaze_y_mm = length_mm(*gaze.y);
  }
  t.left_valid = eye_position(left, t.left_eye_mm);
  t.right_valid = eye_position(right, t.right_eye_mm);
  return t;
}

Result<TrackerStatus> decode_status(const TrackerLayout& l, ReportType type, std::span<const std::uint8_t> report) {
  const ReportRef& ref = type == ReportType::input ? l.status_input : l.status_feature;
  auto values = decode_as(l, type, ref, report, "Tracker Status");
  if (!values) return values.error();
  TrackerStatus s;
  for (const DecodedValue& v : *values) {
    if (v.usage == eye_usage(eye::kConfigurationStatus)) s.configuration_status = static_cast<int>(v.raw);
    else if (v.usage == eye_usage(eye::kSamplingFrequency) && v.in_range && v.value > 0) s.sampling_frequency_hz = v.value;
  }
  return s;
}

Result<TrackerCapabilities> decode_capabilities(const TrackerLayout& l, std::span<const std::uint8_t> report) {
  auto values = decode_as(l, ReportType::feature, l.capabilities, report, "Capabilities");
  if (!values) return values.error();
  TrackerCapabilities c;
  for (const DecodedValue& v : *values) {
    if (!v.in_range) continue;
    switch (usage_id(v.usage)) {
      case eye::kTrackerQuality: c.tracker_quality = static_cast<int>(v.raw); break;
      case eye::kMinimumTrackingDistance: c.minimum_distance_mm = length_mm(v); break;
      case eye::kOptimumTrackingDistance: c.optimum_distance_mm = length_mm(v); break;
      case eye::kMaximumTrackingDistance: c.maximum_distance_mm = length_mm(v); break;
      case eye::kMaximumScreenPlaneWidth: c.max_screen_width_mm = length_mm(v); break;
      case eye::kMaximumScreenPlaneHeight: c.max_screen_height_mm = length_mm(v); break;
      default: break;
    }
  }
  return c;
}

Result<TrackerConfiguration> decode_configuration(const TrackerLayout& l, std::span<const std::uint8_t> report) {
  auto values = decode_as(l, ReportType::feature, l.configuration, report, "Configuration");
  if (!values) return values.error();
  TrackerConfiguration c;
  for (const DecodedValue& v : *values) {
    if (!v.in_range || usage_page(v.usage) != kEyeTrackerPage) continue;
    const auto raw = static_cast<std::uint32_t>(v.raw);
    switch (usage_id(v.usage)) {
      case eye::kDisplayManufacturerId: c.display_manufacturer_id = raw; break;
      case eye::kDisplayProductId: c.display_product_id = raw; break;
      case eye::kDisplaySerialNumber: c.display_serial = raw; break;
      case eye::kDisplayManufacturerDate: c.display_date = raw; break;
      case eye::kCalibratedScreenWidth: c.screen_width_mm = length_mm(v); break;
      case eye::kCalibratedScreenHeight: c.screen_height_mm = length_mm(v); break;
      default: break;
    }
  }
  return c;
}

Result<std::vector<std::uint8_t>> encode_mode_request(const TrackerLayout& l, std::uint8_t mode) {
  if (!l.control.present) return bad_input("hid tracker: the descriptor has no Tracker Control report");
  std::vector<std::uint8_t> report(l.control.bytes, 0);
  const std::size_t skip = l.descriptor.uses_report_ids ? 1 : 0;
  if (skip) report[0] = l.control.id;
  for (const Field& f : l.descriptor.fields) {
    if (f.type != ReportType::feature || f.report_id != l.control.id) continue;
    for (std::uint32_t k = 0; k < f.count; ++k) {
      if (f.usage_of(k) != eye_usage(eye::kModeRequest)) continue;
      if (mode < f.logical_min || mode > f.logical_max)
        return bad_input("hid tracker: mode " + std::to_string(mode) + " is outside the Mode Request range [" +
                         std::to_string(f.logical_min) + ", " + std::to_string(f.logical_max) + "]");
      std::vector<std::uint8_t> payload(report.begin() + static_cast<std::ptrdiff_t>(skip), report.end());
      insert_bits(payload, f.bit_offset + k * f.size, f.size, mode);
      std::copy(payload.begin(), payload.end(), report.begin() + static_cast<std::ptrdiff_t>(skip));
      return report;
    }
  }
  return bad_input("hid tracker: the Tracker Control report has no Mode Request field");
}

}  // namespace foveal::hid

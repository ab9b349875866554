#include "foveal/drivers/hid/report_decoder.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

namespace foveal::hid {

std::uint32_t extract_bits(std::span<const std::uint8_t> data, std::uint32_t bit_offset, std::uint32_t bits) {
  std::uint64_t v = 0;
  const std::uint32_t first = bit_offset / 8, last = (bit_offset + bits - 1) / 8;
  for (std::uint32_t b = first; b <= last; ++b) v |= static_cast<std::uint64_t>(data[b]) << (8 * (b - first));
  v >>= bit_offset % 8;
  return static_cast<std::uint32_t>(bits >= 32 ? v : v & ((1ull << bits) - 1));
}

Result<std::vector<DecodedValue>> decode_report(const ReportDescriptor& d, ReportType type,
                                                std::span<const std::uint8_t> report) {
  std::uint8_t id = 0;
  std::span<const std::uint8_t> payload = report;
  if (d.uses_report_ids) {
    if (report.empty()) return bad_input("report: empty (expected a report ID byte)");
    id = report[0];
    payload = report.subspan(1);
  }
  const ReportInfo* info = d.find_report(type, id);
  if (!info)
    return bad_input("report: no " + std::string(report_type_name(type)) + " report with ID " + std::to_string(id) +
                     " in the descriptor");
  const std::uint32_t need = info->bytes(d.uses_report_ids);
  if (report.size() < need)
    return bad_input("report " + std::to_string(id) + ": truncated: " + std::to_string(report.size()) +
                     " bytes, the descriptor says " + std::to_string(need));
  std::vector<DecodedValue> out;
  for (const Field& f : d.fields) {
    if (f.type != type || f.report_id != id) continue;
    for (std::uint32_t k = 0; k < f.count; ++k) {
      DecodedValue v;
      v.field = &f;
      v.index = k;
      const std::uint32_t bits = extract_bits(payload, f.bit_offset + k * f.size, f.size);
      if (f.is_signed() && f.size < 32 && (bits >> (f.size - 1)) & 1u)
        v.raw = static_cast<std::int64_t>(bits) - (std::int64_t{1} << f.size);
      else if (f.is_signed())
        v.raw = static_cast<std::int32_t>(bits);
      else
        v.raw = bits;
      v.in_range = v.raw >= f.logical_min && v.raw <= f.logical_max;
      if (f.is_variable()) {
        v.usage = f.usage_of(k);
      } else {  // array: the value selects a usage
        const std::int64_t idx = v.raw - f.logical_min;
        v.usage = idx >= 0 ? f.usage_of(static_cast<std::uint32_t>(idx)) : 0;
      }
      double phys = static_cast<double>(v.raw);
      if ((f.physical_min != 0 || f.physical_max != 0) && f.logical_max != f.logical_min)
        phys = f.physical_min + (phys - f.logical_min) * (static_cast<double>(f.physical_max) - f.physical_min) /
                                    (static_cast<double>(f.logical_max) - f.logical_min);
      v.value = phys * std::pow(10.0, f.unit_exponent);
      out.push_back(v);
    }
  }
  return out;
}

namespace {

constexpr Usage kHutrr74Timestamp = make_usage(0x12, 0x20);

std::uint32_t bit_offset_of(const DecodedValue& v) { return v.field->bit_offset + v.index * v.field->size; }

// Whether `v` can continue a multi-byte run whose previous part is `prev`.
bool continues_run(const DecodedValue& prev, const DecodedValue& v) {
  return v.usage == prev.usage && v.field->size == 8 && bit_offset_of(v) == bit_offset_of(prev) + 8;
}

bool may_start_run(const DecodedValue& v) {
  return v.field->size == 8 && v.field->is_variable() && (v.usage == kHutrr74Timestamp || (v.field->flags & kBufferedBytes) != 0);
}

}  // namespace

std::vector<ReportValue> join_multi_byte_values(std::span<const DecodedValue> values) {
  std::vector<ReportValue> out;
  for (std::size_t k = 0; k < values.size();) {
    const DecodedValue& v = values[k];
    std::size_t n = 1;
    if (may_start_run(v))
      while (n < 8 && k + n < values.size() && continues_run(values[k + n - 1], values[k + n])) ++n;
    ReportValue r;
    r.first = &v;
    r.bit_offset = bit_offset_of(v);
    r.bits = v.field->size * static_cast<std::uint32_t>(n);
    if (n == 1) {
      r.raw = v.raw, r.value = v.value, r.in_range = v.in_range;
    } else {
      std::uint64_t number = 0;
      for (std::size_t b = 0; b < n; ++b) {
        const auto byte = static_cast<std::uint8_t>(values[k + b].raw & 0xFF);
        r.bytes.push_back(byte);
        number |= static_cast<std::uint64_t>(byte) << (8 * b);
      }
      r.in_range = number <= static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
      r.raw = r.in_range ? static_cast<std::int64_t>(number) : std::numeric_limits<std::int64_t>::max();
      r.value = static_cast<double>(number) * std::pow(10.0, v.field->unit_exponent);
    }
    out.push_back(std::move(r));
    k += n;
  }
  return out;
}

std::string scaled_decimal(std::int64_t raw, int exponent) {
  const bool negative = raw < 0;
  // The magnitude as digits (INT64_MIN included).
  std::string digits = std::to_string(raw);
  if (negative) digits.erase(0, 1);
  if (exponent >= 0) {
    if (digits != "0") digits.append(static_cast<std::size_t>(exponent), '0');
  } else {
    const auto places = static_cast<std::size_t>(-exponent);
    if (digits.size() <= places) digits.insert(0, places - digits.size() + 1, '0');
    digits.insert(digits.size() - places, ".");
    while (digits.back() == '0') digits.pop_back();
    if (digits.back() == '.') digits.pop_back();
  }
  return (negative && digits != "0" ? "-" : "") + digits;
}

std::string unit_name(std::uint32_t unit) {
  if (unit == 0) return "";
  const int system = static_cast<int>(unit & 0xF);
  static const char* const kSi[] = {"cm", "g", "s", "K", "A", "cd"};
  static const char* const kSiRot[] = {"rad", "g", "s", "K", "A", "cd"};
  static const char* const kEng[] = {"in", "slug", "s", "F", "A", "cd"};
  static const char* const kEngRot[] = {"deg", "slug", "s", "F", "A", "cd"};
  const char* const* names = system == 1 ? kSi : system == 2 ? kSiRot : system == 3 ? kEng : system == 4 ? kEngRot : nullptr;
  if (!names) return "unit 0x" + std::to_string(unit);
  std::string s;
  for (int n = 1; n <= 6; ++n) {
    int e = static_cast<int>((unit >> (4 * n)) & 0xF);
    if (e == 0) continue;
    if (e >= 8) e -= 16;
    if (!s.empty()) s += " ";
    s += names[n - 1];
    if (e != 1) s += "^" + std::to_string(e);
  }
  return s;
}

std::string usage_name(Usage u) {
  static const std::map<Usage, const char*> kNames = {
      {make_usage(0x12, 0x01), "Eye Tracker"},         {make_usage(0x12, 0x02), "Head Tracker"},
      {make_usage(0x12, 0x10), "Tracking Data"},       {make_usage(0x12, 0x11), "Capabilities"},
      {make_usage(0x12, 0x12), "Configuration"},       {make_usage(0x12, 0x13), "Tracker Status"},
      {make_usage(0x12, 0x14), "Tracker Control"},     {make_usage(0x12, 0x20), "Timestamp"},
      {make_usage(0x12, 0x21), "Position X"},          {make_usage(0x12, 0x22), "Position Y"},
      {make_usage(0x12, 0x23), "Position Z"},          {make_usage(0x12, 0x24), "Gaze Location"},
      {make_usage(0x12, 0x25), "Left Eye Position"},   {make_usage(0x12, 0x26), "Right Eye Position"},
      {make_usage(0x12, 0x27), "Head Position"},       {make_usage(0x12, 0x28), "Head Direction"},
      {make_usage(0x12, 0x29), "Rotation about X"},    {make_usage(0x12, 0x2A), "Rotation about Y"},
      {make_usage(0x12, 0x2B), "Rotation about Z"},    {make_usage(0x12, 0x100), "Tracker Quality"},
      {make_usage(0x12, 0x101), "Minimum Tracking Distance"}, {make_usage(0x12, 0x102), "Optimum Tracking Distance"},
      {make_usage(0x12, 0x103), "Maximum Tracking Distance"}, {make_usage(0x12, 0x104), "Maximum Screen Plane Width"},
      {make_usage(0x12, 0x105), "Maximum Screen Plane Height"}, {make_usage(0x12, 0x200), "Display Manufacturer ID"},
      {make_usage(0x12, 0x201), "Display Product ID"}, {make_usage(0x12, 0x202), "Display Serial Number"},
      {make_usage(0x12, 0x203), "Display Manufacturer Date"}, {make_usage(0x12, 0x204), "Calibrated Screen Width"},
      {make_usage(0x12, 0x205), "Calibrated Screen Height"}, {make_usage(0x12, 0x300), "Sampling Frequency"},
      {make_usage(0x12, 0x301), "Configuration Status"}, {make_usage(0x12, 0x400), "Device Mode Request"},
  };
  if (auto it = kNames.find(u); it != kNames.end()) return std::string("Eye and Head Trackers/") + it->second;
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%04X:0x%04X", usage_page(u), usage_id(u));
  return buf;
}

}  // namespace foveal::hid

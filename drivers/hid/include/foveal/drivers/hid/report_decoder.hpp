#pragma once
// Decodes one report's bytes with a parsed descriptor: every field, raw and scaled.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "foveal/core/error.hpp"
#include "foveal/drivers/hid/report_descriptor.hpp"

namespace foveal::hid {

struct DecodedValue {
  const Field* field = nullptr;
  std::uint32_t index = 0;   ///< which of the field's `count` values
  Usage usage = 0;           ///< variable items: the field's usage; arrays: the selected usage
  std::int64_t raw = 0;      ///< logical value (sign-extended when the logical minimum is negative)
  double value = 0;          ///< physical value × 10^unit_exponent, in the unit's base
  bool in_range = true;      ///< raw within [logical_min, logical_max]
};

/// Decodes `report` (starting with the report ID byte when the descriptor uses IDs).
/// Errors: unknown report ID, report shorter than its descriptor says (truncated).
Result<std::vector<DecodedValue>> decode_report(const ReportDescriptor& d, ReportType type,
                                                std::span<const std::uint8_t> report);

/// A value as a reader means it: one decoded value, or a run of 8-bit values that
/// together hold one little-endian number. HUTRR74 declares its 64-bit Timestamp as eight
/// 8-bit values of one usage (so does the Microsoft reference descriptor); a field with
/// HID's Buffered Bytes flag says the same of its bytes.
struct ReportValue {
  const DecodedValue* first = nullptr;  ///< field, usage and bit offset of the (first) part
  std::uint32_t bit_offset = 0;         ///< in the report's payload
  std::uint32_t bits = 0;               ///< the whole value's size
  std::int64_t raw = 0;                 ///< a run: its number (unsigned; > 2^63 - 1 is out of range)
  double value = 0;                     ///< a run: raw × 10^unit_exponent, in the unit's base
  bool in_range = true;
  std::vector<std::uint8_t> bytes;      ///< a run's bytes in report order; empty for one value
  bool is_run() const { return !bytes.empty(); }
};

/// `values` (from decode_report) with each multi-byte run (2 to 8 adjacent 8-bit values
/// of one usage, that usage HUTRR74's Timestamp or the field Buffered Bytes) joined.
std::vector<ReportValue> join_multi_byte_values(std::span<const DecodedValue> values);

/// raw × 10^exponent written out exactly: (123456789, -6) -> "123.456789", (-15, 1) -> "-150".
std::string scaled_decimal(std::int64_t raw, int exponent);

/// Reads `bits` bits at `bit_offset` (little-endian, HID order) from `data`.
std::uint32_t extract_bits(std::span<const std::uint8_t> data, std::uint32_t bit_offset, std::uint32_t bits);

/// "cm", "s", "cm^2 s^-1", ... for a HID unit code; "" for none.
std::string unit_name(std::uint32_t unit);
/// A readable name for a usage, e.g. "Eye and Head Trackers/Gaze Location", else hex.
std::string usage_name(Usage u);

}  // namespace foveal::hid

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

/// Reads `bits` bits at `bit_offset` (little-endian, HID order) from `data`.
std::uint32_t extract_bits(std::span<const std::uint8_t> data, std::uint32_t bit_offset, std::uint32_t bits);

/// "cm", "s", "cm^2 s^-1", ... for a HID unit code; "" for none.
std::string unit_name(std::uint32_t unit);
/// A readable name for a usage, e.g. "Eye and Head Trackers/Gaze Location", else hex.
std::string usage_name(Usage u);

}  // namespace foveal::hid

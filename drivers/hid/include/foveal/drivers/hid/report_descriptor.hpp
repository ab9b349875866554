#pragma once
// A complete HID report-descriptor parser (HID 1.11 §6.2.2): main, global and local
// items, push/pop, report IDs, usage pages, usage ranges and extended usages, signed
// logical ranges, units and unit exponents, nested collections. Device data never
// crashes it: malformed descriptors come back as errors naming the byte offset.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "foveal/core/error.hpp"

namespace foveal::hid {

enum class ReportType : std::uint8_t { input, output, feature };
const char* report_type_name(ReportType t);

/// Main-item data flags (HID 1.11 §6.2.2.5), bit 0..8.
enum FieldFlags : std::uint32_t {
  kConstant = 1u << 0,  ///< set on real eye trackers' data fields too: not padding by itself
  kVariable = 1u << 1,  ///< clear: an array of usage indices
  kRelative = 1u << 2,
  kWrap = 1u << 3,
  kNonLinear = 1u << 4,
  kNoPreferred = 1u << 5,
  kNullState = 1u << 6,
  kVolatile = 1u << 7,
  kBufferedBytes = 1u << 8,
};

/// A usage as page << 16 | id.
using Usage = std::uint32_t;
constexpr Usage make_usage(std::uint16_t page, std::uint16_t id) { return (Usage{page} << 16) | id; }
constexpr std::uint16_t usage_page(Usage u) { return static_cast<std::uint16_t>(u >> 16); }
constexpr std::uint16_t usage_id(Usage u) { return static_cast<std::uint16_t>(u & 0xFFFF); }

struct Collection {
  std::uint8_t type = 0;  ///< 0 physical, 1 application, 2 logical, ...
  Usage usage = 0;
  int parent = -1;        ///< index into ReportDescriptor::collections, -1 at top level
};

/// One main item's worth of fields: `count` fields of `size` bits from `bit_offset`
/// (offsets count from the first byte after the report ID).
struct Field {
  ReportType type = ReportType::input;
  std::uint8_t report_id = 0;
  std::uint32_t bit_offset = 0;
  std::uint32_t size = 0;   ///< bits per field, 1..32
  std::uint32_t count = 0;
  std::uint32_t flags = 0;
  std::vector<Usage> usages;  ///< variable: one per field (last repeats); array: the usage table
  Usage usage_min = 0, usage_max = 0;  ///< a usage range, when one was given
  std::int32_t logical_min = 0, logical_max = 0;
  std::int32_t physical_min = 0, physical_max = 0;
  std::uint32_t unit = 0;
  std::int8_t unit_exponent = 0;
  int collection = -1;      ///< innermost enclosing collection

  bool is_signed() const { return logical_min < 0; }
  bool is_variable() const { return (flags & kVariable) != 0; }
  /// The usage of field i (variable items).
  Usage usage_of(std::uint32_t i) const;
};

struct ReportInfo {
  ReportType type = ReportType::input;
  std::uint8_t id = 0;
  std::uint32_t bits = 0;  ///< payload bits (without the ID byte)
  /// Bytes on the wire: the payload rounded up, plus one for the ID if IDs are used.
  std::uint32_t bytes(bool with_id) const { return (bits + 7) / 8 + (with_id ? 1u : 0u); }
};

struct ReportDescriptor {
  std::vector<Collection> collections;
  std::vector<Field> fields;
  std::vector<ReportInfo> reports;
  bool uses_report_ids = false;

  /// The report of that type and id, or nullptr.
  const ReportInfo* find_report(ReportType type, std::uint8_t id) const;
  /// True if a top-level application collection has this usage.
  bool has_application(Usage usage) const;
  /// The collection path of a field, outermost first.
  std::vector<Usage> collection_path(const Field& f) const;
};

/// Parses a report descriptor. Rejects: truncated items, unbalanced collections,
/// pop without push, report size 0 or > 32 bits, report count > 4096, report ID 0,
/// reports longer than 64 KiB, and fields before any usage page is known when usages
/// are 16-bit. Errors name the byte offset of the item.
Result<ReportDescriptor> parse_report_descriptor(std::span<const std::uint8_t> bytes);

/// Parses "05 12 09 01 ..." (whitespace, commas and 0x prefixes allowed).
Result<std::vector<std::uint8_t>> parse_hex_bytes(const std::string& text);

}  // namespace foveal::hid

#include "foveal/drivers/hid/report_descriptor.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <utility>

namespace foveal::hid {

namespace {

constexpr std::uint32_t kMaxReportCount = 4096;
constexpr std::uint32_t kMaxReportBits = 65536 * 8;
constexpr std::size_t kMaxPushDepth = 16;
constexpr std::size_t kMaxCollectionDepth = 32;

struct GlobalState {
  std::uint16_t usage_page = 0;
  std::int32_t logical_min = 0, logical_max = 0;
  std::uint32_t logical_max_raw = 0;
  int logical_max_size = 0;
  std::int32_t physical_min = 0, physical_max = 0;
  std::int8_t unit_exponent = 0;
  std::uint32_t unit = 0;
  std::uint32_t report_size = 0;
  std::uint8_t report_id = 0;
  std::uint32_t report_count = 0;
};

struct LocalState {
  std::vector<Usage> usages;
  bool have_min = false, have_max = false;
  Usage usage_min = 0, usage_max = 0;
  void clear() { *this = LocalState{}; }
};

std::int32_t sign_extend(std::uint32_t v, int size) {
  if (size == 1) return static_cast<std::int8_t>(v);
  if (size == 2) return static_cast<std::int16_t>(v);
  return static_cast<std::int32_t>(v);
}

std::string at(std::size_t offset) { return "report descriptor byte " + std::to_string(offset) + ": "; }

}  // namespace

const char* report_type_name(ReportType t) {
  switch (t) {
    case ReportType::input: return "input";
    case ReportType::output: return "output";
    case ReportType::feature: return "feature";
  }
  return "?";
}

Usage Field::usage_of(std::uint32_t i) const {
  if (!usages.empty()) return usages[std::min<std::size_t>(i, usages.size() - 1)];
  if (usage_max >= usage_min && usage_max != 0) return std::min<Usage>(usage_min + i, usage_max);
  return 0;
}

const ReportInfo* ReportDescriptor::find_report(ReportType type, std::uint8_t id) const {
  for (const ReportInfo& r : reports)
    if (r.type == type && r.id == id) return &r;
  return nullptr;
}

bool ReportDescriptor::has_application(Usage usage) const {
  return std::any_of(collections.begin(), collections.end(),
                     [&](const Collection& c) { return c.parent < 0 && c.type == 1 && c.usage == usage; });
}

std::vector<Usage> ReportDescriptor::collection_path(const Field& f) const {
  std::vector<Usage> path;
  for (int c = f.collection; c >= 0 && c < static_cast<int>(collections.size()); c = collections[c].parent)
    path.push_back(collections[c].usage);
  std::reverse(path.begin(), path.end());
  return path;
}

Result<ReportDescriptor> parse_report_descriptor(std::span<const std::uint8_t> bytes) {
  ReportDescriptor d;
  GlobalState g;
  std::vector<GlobalState> stack;
  LocalState local;
  std::vector<int> open;  // collection indices
  std::map<std::pair<int, int>, std::uint32_t> bit_pos;  // (type, id) -> bits so far
  int delimiter_depth = 0;

  // A 16-bit usage takes the current page; a 32-bit one carries its own.
  auto full_usage = [&](std::uint32_t v, int size) -> Usage {
    return size == 4 ? v : make_usage(g.usage_page, static_cast<std::uint16_t>(v));
  };

  std::size_t i = 0;
  while (i < bytes.size()) {
    const std::size_t item_at = i;
    const std::uint8_t prefix = bytes[i++];
    if (prefix == 0xFE) {  // long item: size, tag, data; none are defined, skip it
      if (i + 2 > bytes.size()) return bad_input(at(item_at) + "truncated long item");
      const std::size_t len = bytes[i];
      i += 2 + len;
      if (i > bytes.size()) return bad_input(at(item_at) + "truncated long item");
      continue;
    }
    const int size = (prefix & 3) == 3 ? 4 : (prefix & 3);
    const int type = (prefix >> 2) & 3;
    const int tag = prefix >> 4;
    if (i + static_cast<std::size_t>(size) > bytes.size())
      return bad_input(at(item_at) + "item needs " + std::to_string(size) + " data bytes, descriptor ends");
    std::uint32_t u = 0;
    for (int k = 0; k < size; ++k) u |= static_cast<std::uint32_t>(bytes[i + static_cast<std::size_t>(k)]) << (8 * k);
    i += static_cast<std::size_t>(size);
    const std::int32_t s = size ? sign_extend(u, size) : 0;

    if (type == 0) {  // main
      switch (tag) {
        case 0x8: case 0x9: case 0xB: {  // input, output, feature
          const ReportType rt = tag == 0x8 ? ReportType::input : tag == 0x9 ? ReportType::output : ReportType::feature;
          if (g.report_size == 0 || g.report_size > 32)
            return bad_input(at(item_at) + "report size " + std::to_string(g.report_size) + " bits (1..32 supported)");
          if (g.report_count > kMaxReportCount)
            return bad_input(at(item_at) + "report count " + std::to_string(g.report_count) + " too large");
          Field f;
          f.type = rt;
          f.report_id = g.report_id;
          f.size = g.report_size;
          f.count = g.report_count;
          f.flags = u;
          f.usages = local.usages;
          if (local.have_min && local.have_max) {
            f.usage_min = local.usage_min;
            f.usage_max = local.usage_max;
          }
          f.logical_min = g.logical_min;
          // A positive minimum with a maximum that only fits unsigned (26 FF 00 is
          // common, 25 FF less so): read the maximum as unsigned, as hosts do.
          f.logical_max = g.logical_max;
          if (g.logical_min >= 0 && g.logical_max < 0 && g.logical_max_size < 4)
            f.logical_max = static_cast<std::int32_t>(g.logical_max_raw);
          f.physical_min = g.physical_min;
          f.physical_max = g.physical_max;
          f.unit = g.unit;
          f.unit_exponent = g.unit_exponent;
          f.collection = open.empty() ? -1 : open.back();
          std::uint32_t& pos = bit_pos[{static_cast<int>(rt), g.report_id}];
          f.bit_offset = pos;
          pos += f.size * f.count;
          if (pos > kMaxReportBits) return bad_input(at(item_at) + "report longer than 64 KiB");
          d.fields.push_back(std::move(f));
          break;
        }
        case 0xA: {  // collection
          if (open.size() >= kMaxCollectionDepth) return bad_input(at(item_at) + "collections nested too deep");
          Collection c;
          c.type = static_cast<std::uint8_t>(u);
          c.usage = local.usages.empty() ? (local.have_min ? local.usage_min : 0) : local.usages.front();
          c.parent = open.empty() ? -1 : open.back();
          d.collections.push_back(c);
          open.push_back(static_cast<int>(d.collections.size() - 1));
          break;
        }
        case 0xC:  // end collection
          if (open.empty()) return bad_input(at(item_at) + "End Collection without a Collection");
          open.pop_back();
          break;
        default:
          return bad_input(at(item_at) + "unknown main item tag 0x" + std::to_string(tag));
      }
      local.clear();
    } else if (type == 1) {  // global
      switch (tag) {
        case 0x0: g.usage_page = static_cast<std::uint16_t>(u); break;
        case 0x1: g.logical_min = s; break;
        case 0x2: g.logical_max = s; g.logical_max_raw = u; g.logical_max_size = size; break;
        case 0x3: g.physical_min = s; break;
        case 0x4: g.physical_max = s; break;
        case 0x5: {  // unit exponent: a 4-bit two's complement nibble
          const int nib = static_cast<int>(u & 0xF);
          g.unit_exponent = static_cast<std::int8_t>(nib >= 8 ? nib - 16 : nib);
          break;
        }
        case 0x6: g.unit = u; break;
        case 0x7: g.report_size = u; break;
        case 0x8:
          if (u == 0 || u > 255) return bad_input(at(item_at) + "report ID " + std::to_string(u) + " (1..255 allowed)");
          g.report_id = static_cast<std::uint8_t>(u);
          d.uses_report_ids = true;
          break;
        case 0x9: g.report_count = u; break;
        case 0xA:
          if (stack.size() >= kMaxPushDepth) return bad_input(at(item_at) + "Push nested too deep");
          stack.push_back(g);
          break;
        case 0xB:
          if (stack.empty()) return bad_input(at(item_at) + "Pop without Push");
          g = stack.back();
          stack.pop_back();
          break;
        default:
          return bad_input(at(item_at) + "unknown global item tag 0x" + std::to_string(tag));
      }
    } else if (type == 2) {  // local
      switch (tag) {
        case 0x0:
          if (local.usages.size() >= kMaxReportCount) return bad_input(at(item_at) + "too many usages");
          local.usages.push_back(full_usage(u, size));
          break;
        case 0x1: local.usage_min = full_usage(u, size); local.have_min = true; break;
        case 0x2: local.usage_max = full_usage(u, size); local.have_max = true; break;
        case 0xA:  // delimiter: alternative usages; keep the first set
          delimiter_depth += u ? 1 : -1;
          if (delimiter_depth < 0 || delimiter_depth > 1) return bad_input(at(item_at) + "unbalanced Delimiter");
          break;
        default: break;  // designators and strings: not needed here
      }
    } else {
      return bad_input(at(item_at) + "reserved item type");
    }
  }
  if (!open.empty()) return bad_input("report descriptor: " + std::to_string(open.size()) + " collection(s) not closed");
  if (d.fields.empty()) return bad_input("report descriptor: no input, output or feature items");
  for (const auto& [key, bits] : bit_pos) {
    ReportInfo r;
    r.type = static_cast<ReportType>(key.first);
    r.id = static_cast<std::uint8_t>(key.second);
    r.bits = bits;
    d.reports.push_back(r);
  }
  return d;
}

Result<std::vector<std::uint8_t>> parse_hex_bytes(const std::string& text) {
  std::vector<std::uint8_t> out;
  std::size_t i = 0;
  auto hexval = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    return -1;
  };
  while (i < text.size()) {
    const char c = text[i];
    if (std::isspace(static_cast<unsigned char>(c)) || c == ',' || c == ':') {
      ++i;
      continue;
    }
    if (c == '0' && i + 1 < text.size() && (text[i + 1] == 'x' || text[i + 1] == 'X')) {
      i += 2;
      continue;
    }
    if (i + 1 >= text.size() || hexval(c) < 0 || hexval(text[i + 1]) < 0)
      return bad_input("hex text: character " + std::to_string(i + 1) + ": expected two hex digits");
    out.push_back(static_cast<std::uint8_t>(hexval(c) * 16 + hexval(text[i + 1])));
    i += 2;
  }
  return out;
}

}  // namespace foveal::hid

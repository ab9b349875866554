#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>

#include "commands.hpp"
#include "foveal/core/read_file.hpp"
#include "foveal/drivers/hid/report_decoder.hpp"
#include "foveal/runtime/cli.hpp"

namespace foveal::cmd {

namespace {

// An argument is a file holding hex text if such a path exists (it must be a regular
// file: a directory or a FIFO is an error, not hex text), else hex text itself.
Result<std::vector<std::uint8_t>> hex_argument(const std::string& arg, const char* what) {
  constexpr std::size_t kMaxHexFileBytes = std::size_t{1} << 20;  // descriptors are < 4 KiB of bytes
  std::string text = arg;
  std::error_code ec;
  if (std::filesystem::exists(std::filesystem::symlink_status(arg, ec))) {
    auto file = read_regular_file(arg, kMaxHexFileBytes, std::string(what) + " file");
    if (!file) return file.error();
    text = std::move(*file);
  }
  auto bytes = hid::parse_hex_bytes(text);
  if (!bytes) return bad_input(std::string(what) + ": " + bytes.error().message);
  if (bytes->empty()) return bad_input(std::string(what) + ": no bytes");
  return bytes;
}

}  // namespace

void add_hid(CLI::App& app, int& exit_code) {
  CLI::App* hid_cmd = app.add_subcommand("hid", "HID tools for debugging eye trackers");
  hid_cmd->require_subcommand(1);
  struct Args {
    std::string descriptor, report, type = "input";
    bool json = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* dec = hid_cmd->add_subcommand("decode", "Decode a report with a report descriptor, field by field");
  dec->add_option("--descriptor", args->descriptor, "Report descriptor: hex bytes, or a file holding them")->required();
  dec->add_option("--report", args->report, "Report bytes (hex, with the report ID first), or a file; omit to list the descriptor's fields");
  dec->add_option("--type", args->type, "Report type")->check(CLI::IsMember({"input", "output", "feature"}))->capture_default_str();
  dec->add_flag("--json", args->json, "Print JSON");
  dec->callback([args, &exit_code] {
    auto desc_bytes = hex_argument(args->descriptor, "--descriptor");
    if (!desc_bytes) {
      exit_code = cli::report(desc_bytes.error());
      return;
    }
    auto desc = hid::parse_report_descriptor(*desc_bytes);
    if (!desc) {
      exit_code = cli::report(desc.error());
      return;
    }
    const hid::ReportType type = args->type == "input" ? hid::ReportType::input
                                 : args->type == "output" ? hid::ReportType::output : hid::ReportType::feature;
    nlohmann::json j;
    j["descriptor_bytes"] = desc_bytes->size();
    j["uses_report_ids"] = desc->uses_report_ids;
    for (const hid::ReportInfo& r : desc->reports)
      j["reports"].push_back({{"type", hid::report_type_name(r.type)}, {"id", r.id}, {"bytes", r.bytes(desc->uses_report_ids)}});
    if (args->report.empty()) {
      for (const hid::Field& f : desc->fields)
        j["fields"].push_back({{"type", hid::report_type_name(f.type)}, {"report_id", f.report_id},
                               {"usage", hid::usage_name(f.usage_of(0))}, {"bit_offset", f.bit_offset},
                               {"size", f.size}, {"count", f.count}, {"flags", f.flags},
                               {"logical_min", f.logical_min}, {"logical_max", f.logical_max},
                               {"unit", hid::unit_name(f.unit)}, {"unit_exponent", f.unit_exponent}});
    } else {
      auto report = hex_argument(args->report, "--report");
      if (!report) {
        exit_code = cli::report(report.error());
        return;
      }
      auto values = hid::decode_report(*desc, type, *report);
      if (!values) {
        exit_code = cli::report(values.error());
        return;
      }
      // Multi-byte numbers (the HUTRR74 timestamp's eight bytes) as one value each.
      j["values"] = nlohmann::json::array();
      for (const hid::ReportValue& r : hid::join_multi_byte_values(*values)) {
        const hid::Field& f = *r.first->field;
        std::string path;
        for (hid::Usage u : desc->collection_path(f)) path += hid::usage_name(u) + " > ";
        nlohmann::json v = {{"usage", hid::usage_name(r.first->usage)}, {"collection", path}, {"bit_offset", r.bit_offset},
                            {"size", r.bits}, {"raw", r.raw}, {"value", r.value}, {"unit", hid::unit_name(f.unit)},
                            {"exponent", f.unit_exponent}, {"constant_flag", (f.flags & hid::kConstant) != 0},
                            {"in_range", r.in_range}};
        if (r.is_run()) {
          v["bytes"] = r.bytes;
          v["decimal"] = hid::scaled_decimal(r.raw, f.unit_exponent);
        }
        j["values"].push_back(std::move(v));
      }
    }
    if (args->json) {
      cli::print_json(j);
      return;
    }
    std::printf("descriptor: %zu bytes, report IDs %s\n", desc_bytes->size(), desc->uses_report_ids ? "yes" : "no");
    for (const auto& r : j["reports"])
      std::printf("  %-7s report %3d: %d bytes\n", r["type"].get<std::string>().c_str(), r["id"].get<int>(), r["bytes"].get<int>());
    if (j.contains("fields"))
      for (const auto& f : j["fields"])
        std::printf("  %-7s id %3d bit %4d  %2dx%-3d %s\n", f["type"].get<std::string>().c_str(), f["report_id"].get<int>(),
                    f["bit_offset"].get<int>(), f["size"].get<int>(), f["count"].get<int>(), f["usage"].get<std::string>().c_str());
    if (j.contains("values"))
      for (const auto& v : j["values"]) {
        char value[64];
        std::snprintf(value, sizeof value, "%.6g", v["value"].get<double>());
        std::string bytes;
        if (v.contains("bytes")) {
          for (int b : v["bytes"]) {
            char hex[4];
            std::snprintf(hex, sizeof hex, " %02x", b);
            bytes += hex;
          }
          bytes = "  (" + std::to_string(v["bytes"].size()) + " bytes:" + bytes + ")";
        }
        std::printf("  bit %4d %2d  %-40s raw %12lld  = %s %s%s\n", v["bit_offset"].get<int>(), v["size"].get<int>(),
                    v["usage"].get<std::string>().c_str(), v["raw"].get<long long>(),
                    v.contains("decimal") ? v["decimal"].get<std::string>().c_str() : value, v["unit"].get<std::string>().c_str(),
                    bytes.c_str());
      }
  });
}

}  // namespace foveal::cmd

#include "foveal/drivers/probe.hpp"

#include <algorithm>

#include "auto_device.hpp"
#include "driver_entry.hpp"

namespace foveal::probe {

namespace {

const DriverEntry* find_driver(const std::string& name) {
  for (const DriverEntry& e : driver_list())
    if (name == e.name) return &e;
  return nullptr;
}

std::string known_drivers() {
  std::string s;
  for (const DriverEntry& e : driver_list()) s += std::string(s.empty() ? "" : ", ") + e.usage;
  return s + ", auto";
}

}  // namespace

Result<SourceSpec> parse_source_spec(const std::string& text) {
  const auto colon = text.find(':');
  SourceSpec spec{text.substr(0, colon), colon == std::string::npos ? "" : text.substr(colon + 1)};
  const bool has_arg = colon != std::string::npos;
  if (spec.driver == "auto") {
    if (has_arg) return bad_input("--source " + text + ": auto takes no argument");
    return spec;
  }
  const DriverEntry* e = find_driver(spec.driver);
  if (!e) {
    for (const std::string& out : drivers_left_out())
      if (out == spec.driver)
        return bad_input("--source " + text + ": this build has no '" + out + "' driver (see the FOVEAL_DRIVER_* CMake options)");
    return bad_input("--source " + text + ": unknown source '" + spec.driver + "' (" + known_drivers() + ")");
  }
  if (e->arg == DriverEntry::Arg::required && spec.arg.empty())
    return bad_input("--source " + text + ": expected " + e->usage);
  if (e->arg == DriverEntry::Arg::none && has_arg) return bad_input("--source " + text + ": " + e->name + " takes no argument");
  return spec;
}

std::string device_spec(const std::string& device) {
  if (device.empty()) return "auto";
  if (device.find(':') != std::string::npos || find_driver(device) || device == "auto") return device;
  if (std::all_of(device.begin(), device.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    if (auto rows = list_devices(false); rows)
      for (const DeviceRow& r : *rows)
        if (std::to_string(r.id) == device) return r.spec;
    return "hid:" + device;  // make_source names the missing id
  }
  return "hid:" + device;
}

std::string source_spec_help() {
  std::string s;
  for (const DriverEntry& e : driver_list()) s += std::string("  ") + e.usage + ": " + e.what + "\n";
  s += "  auto: the first live tracker found (";
  bool first = true;
  for (const DriverEntry& e : driver_list())
    if (e.live) s += std::string(first ? "" : ", ") + e.name, first = false;
  return s + ")\n";
}

Result<OpenedSource> make_source(const SourceSpec& spec, const SourceOptions& options) {
  if (spec.driver == "auto") {
    auto src = std::make_unique<AutoSource>(options);
    const AutoSource* raw = src.get();
    return OpenedSource{std::move(src), spec, true, [raw] { return raw->counters(); }};
  }
  const DriverEntry* e = find_driver(spec.driver);
  if (!e) return parse_source_spec(spec.text()).error();
  return e->make(spec.arg, options);
}

Result<std::vector<DeviceRow>> list_devices(bool probe_rate) {
  std::vector<DeviceRow> rows;
  for (const DriverEntry& e : driver_list()) {
    if (!e.live) continue;
    auto found = e.list(probe_rate);
    if (!found) return found.error();
    for (DeviceRow& r : *found) {
      r.id = rows.size();
      rows.push_back(std::move(r));
    }
  }
  return rows;
}

nlohmann::json device_json(const DeviceRow& r) {
  return {{"id", r.id},           {"driver", r.driver}, {"spec", r.spec},       {"path", r.path},
          {"vid_pid", r.vid_pid}, {"name", r.name},     {"serial", r.serial},   {"sample_rate_hz", r.rate_hz},
          {"problem", r.problem}};
}

}  // namespace foveal::probe

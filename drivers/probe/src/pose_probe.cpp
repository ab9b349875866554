// Head-pose specs to pose devices, and the headsets present (docs/headset.md).
#include "auto_device.hpp"
#include "driver_entry.hpp"

namespace foveal::probe {

namespace {

const PoseDriverEntry* find_pose_driver(const std::string& name) {
  for (const PoseDriverEntry& e : pose_driver_list())
    if (name == e.name) return &e;
  return nullptr;
}

std::string known_pose_drivers() {
  std::string s;
  for (const PoseDriverEntry& e : pose_driver_list()) s += std::string(s.empty() ? "" : ", ") + e.usage;
  return s + (s.empty() ? "" : ", ") + "auto";
}

}  // namespace

Result<PoseSpec> parse_pose_spec(const std::string& text) {
  const auto colon = text.find(':');
  PoseSpec spec{text.substr(0, colon), colon == std::string::npos ? "" : text.substr(colon + 1)};
  if (spec.driver == "auto") {
    if (colon != std::string::npos) return bad_input("--head " + text + ": auto takes no argument");
    return spec;
  }
  if (!find_pose_driver(spec.driver)) {
    for (const std::string& out : drivers_left_out())
      if (out == spec.driver || (out == "hid" && spec.driver == "vive"))
        return bad_input("--head " + text + ": this build has no '" + spec.driver + "' driver (see the FOVEAL_DRIVER_* CMake options)");
    return bad_input("--head " + text + ": unknown head-pose source '" + spec.driver + "' (" + known_pose_drivers() + ")");
  }
  if (spec.driver == "psvr2" && colon != std::string::npos) return bad_input("--head " + text + ": psvr2 takes no argument");
  return spec;
}

std::string pose_spec_help() {
  std::string s;
  for (const PoseDriverEntry& e : pose_driver_list()) s += std::string("  ") + e.usage + ": " + e.what + "\n";
  return s + "  auto: the first headset found with a pose\n";
}

Result<OpenedPoseDevice> make_pose_device(const PoseSpec& spec, const SourceOptions& options) {
  if (spec.driver == "auto") {
    auto dev = std::make_unique<AutoPoseDevice>(options);
    const AutoPoseDevice* raw = dev.get();
    auto display = [raw]() -> std::optional<HeadsetDisplay> {  // the chosen headset's, if its driver reads one
      const auto& chosen = raw->current();
      if (!chosen || !chosen->display) return std::nullopt;
      return chosen->display();
    };
    return OpenedPoseDevice{std::move(dev), spec, [raw] { return raw->counters(); }, std::move(display)};
  }
  const PoseDriverEntry* e = find_pose_driver(spec.driver);
  if (!e) return parse_pose_spec(spec.text()).error();
  return e->make(spec.arg, options);
}

Result<std::vector<HmdRow>> list_hmds() {
  std::vector<HmdRow> rows;
  for (const PoseDriverEntry& e : pose_driver_list()) {
    auto found = e.list();
    if (!found) return found.error();
    for (HmdRow& r : *found) {
      r.id = rows.size();
      rows.push_back(std::move(r));
    }
  }
  return rows;
}

#ifndef FOVEAL_HAVE_HID
Result<HeadsetDisplay> display_from_vive_config(const std::string&, const std::string& where) {
  return bad_input(where + ": this build has no Vive driver (FOVEAL_DRIVER_HID)");
}
#endif

nlohmann::json hmd_json(const HmdRow& r) {
  return {{"id", r.id},         {"driver", r.driver},   {"head", r.pose_spec}, {"source", r.gaze_spec},
          {"path", r.path},     {"vid_pid", r.vid_pid}, {"name", r.name},      {"serial", r.serial},
          {"provides", r.provides}, {"problem", r.problem}};
}

}  // namespace foveal::probe

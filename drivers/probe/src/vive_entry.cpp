// vive[:PATH]: an HTC Vive / Vive Pro's IMU (fused to 3DoF) and lens data, through hidapi.
#include "driver_entry.hpp"
#include "foveal/drivers/vive/vive_display_model.hpp"
#include "foveal/drivers/vive/vive_source.hpp"

namespace foveal::probe {

namespace {

Result<HeadsetDisplay> display_from_config(const vive::Config& c) {
  vive::DistortionFit fit;
  auto m = vive::vive_display_model(c, &fit);
  if (!m) return m.error();
  return HeadsetDisplay{*m, vive::vive_model_source(c, fit)};
}

}  // namespace

Result<HeadsetDisplay> display_from_vive_config(const std::string& json, const std::string& where) {
  auto c = vive::parse_config(json, where);
  if (!c) return c.error();
  return display_from_config(*c);
}

PoseDriverEntry vive_pose_entry() {
  PoseDriverEntry e{"vive", "vive[:PATH]",
                    "an HTC Vive / Vive Pro's IMU (3DoF, fused) and its lens data, over hidapi (a hidraw node, or the first one)",
                    {}, {}};
  e.list = []() -> Result<std::vector<HmdRow>> {
    auto backend = hid::make_hidapi_backend();
    auto found = vive::find_vive_devices(*backend);
    if (!found) return found.error();
    std::vector<HmdRow> rows;
    for (const vive::ViveDeviceEntry& d : *found) {
      HmdRow row;
      row.driver = "vive";
      row.pose_spec = "vive:" + d.path;
      row.path = d.path;
      row.vid_pid = hex4(d.vendor_id) + ":" + hex4(d.product_id);
      row.name = d.name;
      row.serial = d.serial;
      row.provides = {"3dof orientation (imu fused)", "imu 1000 Hz", "display model (lens data)"};
      rows.push_back(std::move(row));
    }
    return rows;
  };
  e.make = [](const std::string& arg, const SourceOptions& o) -> Result<OpenedPoseDevice> {
    vive::ViveOptions opts;
    opts.device = arg;
    if (o.log) opts.log = o.log;
    auto dev = std::make_unique<vive::ViveSource>(opts);
    const vive::ViveSource* raw = dev.get();
    OpenedPoseDevice out{std::move(dev), {"vive", arg}, {}, {}};
    out.counters = [raw] {
      const vive::ViveCounters& c = raw->counters();
      return nlohmann::json{{"reports", c.reports},       {"samples", c.samples},           {"malformed", c.malformed},
                            {"other_reports", c.other_reports}, {"opens", c.opens},      {"disconnects", c.disconnects},
                            {"config_errors", c.config_errors}};
    };
    out.display = [raw]() -> std::optional<HeadsetDisplay> {
      if (!raw->config()) return std::nullopt;
      auto d = display_from_config(*raw->config());
      if (!d) return std::nullopt;
      return *d;
    };
    return out;
  };
  return e;
}

}  // namespace foveal::probe

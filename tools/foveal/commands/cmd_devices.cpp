// foveal devices: the eye trackers present, found by what they are (HID usage page
// 0x12, or the PS VR2's USB IDs), with the driver that would read them; the headsets
// present and what each provides (gaze, pose, IMU, lens data); and a headset's own
// display model written as a display-model file.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>

#include "commands.hpp"
#include "foveal/core/atomic_file.hpp"
#include "foveal/core/read_file.hpp"
#include "foveal/drivers/probe.hpp"
#include "foveal/runtime/cli.hpp"

namespace foveal::cmd {

namespace {

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

/// The display model of the first headset that reports one (a Vive), or of a saved
/// configuration file.
Result<probe::HeadsetDisplay> headset_display(const std::string& head, const std::string& config_file) {
  if (!config_file.empty()) {
    auto text = read_regular_file(config_file, 1024 * 1024, "Vive configuration");
    if (!text) return text.error();
    return probe::display_from_vive_config(*text, config_file);
  }
  std::string spec_text = head;
  if (spec_text.empty()) {
    auto rows = probe::list_hmds();
    if (!rows) return rows.error();
    for (const probe::HmdRow& r : *rows)
      if (r.driver == "vive") {
        spec_text = r.pose_spec;
        break;
      }
    if (spec_text.empty())
      return bad_input("--display-model: no headset that reports its lens data (an HTC Vive) found; --head SPEC or --from-config FILE");
  }
  auto spec = probe::parse_pose_spec(spec_text);
  if (!spec) return spec.error();
  auto dev = probe::make_pose_device(*spec);
  if (!dev) return dev.error();
  if (Status s = dev->device->open(); !s) return s.error();
  auto d = dev->display ? dev->display() : std::nullopt;
  dev->device->close();
  if (!d) return bad_input("--display-model: " + spec_text + " reported no readable lens data (see its configuration errors above)");
  return *d;
}

}  // namespace

void add_devices(CLI::App& app, int& exit_code) {
  struct Args {
    bool json = false;
    std::string display_model, head, from_config;
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("devices", "List the eye trackers and headsets present and what each provides");
  sub->add_flag("--json", args->json, "Print the lists as JSON");
  sub->add_option("--display-model", args->display_model,
                  "Write the headset's own display model (read from its lens data: a Vive) to this file (docs/display-model.md)");
  sub->add_option("--head", args->head, "With --display-model: the headset (a --head spec; default: the first Vive)");
  sub->add_option("--from-config", args->from_config,
                  "With --display-model: convert a saved Vive configuration JSON instead of reading a headset");
  sub->callback([args, &exit_code] {
    if ((!args->head.empty() || !args->from_config.empty()) && args->display_model.empty()) {
      exit_code = cli::report(bad_input("devices: --head and --from-config go with --display-model OUT.json"));
      return;
    }
    if (!args->display_model.empty()) {
      auto d = headset_display(args->head, args->from_config);
      if (!d) {
        exit_code = cli::report(d.error());
        return;
      }
      if (Status s = write_file_atomically(args->display_model, d->model.to_json_text(d->source)); !s) {
        exit_code = cli::report(s.error());
        return;
      }
      if (args->json) cli::print_json({{"display_model", args->display_model}, {"name", d->model.name}, {"source", d->source}});
      else std::printf("display model %s -> %s (%s)\n", d->model.name.c_str(), args->display_model.c_str(), d->source.c_str());
      return;
    }
    auto rows = probe::list_devices(true);
    if (!rows) {
      exit_code = cli::report(rows.error());
      return;
    }
    auto hmds = probe::list_hmds();
    if (!hmds) {
      exit_code = cli::report(hmds.error());
      return;
    }
    if (args->json) {
      nlohmann::json list = nlohmann::json::array(), heads = nlohmann::json::array();
      for (const probe::DeviceRow& r : *rows) list.push_back(probe::device_json(r));
      for (const probe::HmdRow& r : *hmds) heads.push_back(probe::hmd_json(r));
      cli::print_json({{"devices", list}, {"headsets", heads}});
      return;
    }
    if (rows->empty()) {
      std::printf("no eye trackers found (drivers: hid, psvr2; docs/drivers.md)\n");
    } else {
      std::printf("%-3s %-7s %-16s %-10s %-10s %s\n", "id", "driver", "path", "vid:pid", "rate", "name");
      for (const probe::DeviceRow& r : *rows) {
        const std::string rate = r.rate_hz > 0 ? std::to_string(static_cast<int>(r.rate_hz + 0.5)) + " Hz" : "unknown";
        const std::string note = r.problem.empty() ? "" : "  (" + r.problem + ")";
        std::printf("%-3zu %-7s %-16s %-10s %-10s %s%s\n", r.id, r.driver.c_str(), r.path.c_str(), r.vid_pid.c_str(),
                    rate.c_str(), r.name.c_str(), note.c_str());
      }
    }
    if (hmds->empty()) {
      std::printf("no headsets with head tracking found (drivers: psvr2, vive; docs/headset.md)\n");
      return;
    }
    std::printf("headsets:\n%-3s %-7s %-22s %-10s %-24s %s\n", "id", "driver", "--head", "vid:pid", "name", "provides");
    for (const probe::HmdRow& r : *hmds)
      std::printf("%-3zu %-7s %-22s %-10s %-24s %s\n", r.id, r.driver.c_str(), r.pose_spec.c_str(), r.vid_pid.c_str(),
                  r.name.c_str(), joined(r.provides).c_str());
  });
}

}  // namespace foveal::cmd

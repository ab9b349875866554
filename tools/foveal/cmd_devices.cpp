// foveal devices: the eye trackers present, found by what they are (HID usage page
// 0x12), with the driver that would read them.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>

#include "commands.hpp"
#include "foveal/drivers/hid/hid_tracker_source.hpp"
#include "foveal/tools/cli.hpp"

namespace foveal::cmd {

namespace {

std::string hex4(std::uint16_t v) {
  char b[8];
  std::snprintf(b, sizeof b, "%04x", v);
  return b;
}

}  // namespace

void add_devices(CLI::App& app, int& exit_code) {
  auto json = std::make_shared<bool>(false);
  CLI::App* sub = app.add_subcommand("devices", "List the eye trackers present (HID usage page 0x12) and their drivers");
  sub->add_flag("--json", *json, "Print the list as JSON");
  sub->callback([json, &exit_code] {
    auto backend = hid::make_hidapi_backend();
    auto trackers = hid::find_eye_trackers(*backend);
    if (!trackers) {
      exit_code = cli::report(trackers.error());
      return;
    }
    nlohmann::json list = nlohmann::json::array();
    for (std::size_t i = 0; i < trackers->size(); ++i) {
      const hid::HidDeviceEntry& d = (*trackers)[i].device;
      // The rate needs the device open; a device we may not open is still listed.
      hid::HidTrackerOptions opts;
      opts.device = d.path;
      opts.log = [](const std::string&) {};
      hid::HidTrackerSource src(opts, backend);
      double rate = 0;
      std::string problem;
      if (Status s = src.open(); s) {
        src.wait_for_rate(std::chrono::milliseconds(600));
        rate = src.status().sampling_frequency_hz;
      } else {
        problem = s.error().message;
      }
      list.push_back({{"id", i},
                      {"driver", "hid"},
                      {"path", d.path},
                      {"vid_pid", hex4(d.vendor_id) + ":" + hex4(d.product_id)},
                      {"name", d.manufacturer.empty() ? d.product : d.manufacturer + " " + d.product},
                      {"serial", d.serial},
                      {"sample_rate_hz", rate},
                      {"problem", problem}});
    }
    if (*json) {
      cli::print_json({{"devices", list}});
      return;
    }
    if (list.empty()) {
      std::printf("no eye trackers found\n");
      return;
    }
    std::printf("%-3s %-7s %-16s %-10s %-10s %s\n", "id", "driver", "path", "vid:pid", "rate", "name");
    for (const auto& d : list) {
      const double rate = d["sample_rate_hz"];
      const std::string rate_text = rate > 0 ? std::to_string(static_cast<int>(rate + 0.5)) + " Hz" : "unknown";
      std::printf("%-3d %-7s %-16s %-10s %-10s %s%s\n", d["id"].get<int>(), d["driver"].get<std::string>().c_str(),
                  d["path"].get<std::string>().c_str(), d["vid_pid"].get<std::string>().c_str(), rate_text.c_str(),
                  d["name"].get<std::string>().c_str(),
                  d["problem"].get<std::string>().empty() ? "" : ("  (" + d["problem"].get<std::string>() + ")").c_str());
    }
  });
}

}  // namespace foveal::cmd

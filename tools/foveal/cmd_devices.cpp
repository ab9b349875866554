// foveal devices: the eye trackers present, found by what they are (HID usage page
// 0x12, or the PS VR2's USB IDs), with the driver that would read them.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>

#include "commands.hpp"
#include "foveal/drivers/probe.hpp"
#include "foveal/tools/cli.hpp"

namespace foveal::cmd {

void add_devices(CLI::App& app, int& exit_code) {
  auto json = std::make_shared<bool>(false);
  CLI::App* sub = app.add_subcommand("devices", "List the eye trackers present and the drivers that read them");
  sub->add_flag("--json", *json, "Print the list as JSON");
  sub->callback([json, &exit_code] {
    auto rows = probe::list_devices(true);
    if (!rows) {
      exit_code = cli::report(rows.error());
      return;
    }
    if (*json) {
      nlohmann::json list = nlohmann::json::array();
      for (const probe::DeviceRow& r : *rows) list.push_back(probe::device_json(r));
      cli::print_json({{"devices", list}});
      return;
    }
    if (rows->empty()) {
      std::printf("no eye trackers found (drivers: hid, psvr2; docs/drivers.md)\n");
      return;
    }
    std::printf("%-3s %-7s %-16s %-10s %-10s %s\n", "id", "driver", "path", "vid:pid", "rate", "name");
    for (const probe::DeviceRow& r : *rows) {
      const std::string rate = r.rate_hz > 0 ? std::to_string(static_cast<int>(r.rate_hz + 0.5)) + " Hz" : "unknown";
      const std::string note = r.problem.empty() ? "" : "  (" + r.problem + ")";
      std::printf("%-3zu %-7s %-16s %-10s %-10s %s%s\n", r.id, r.driver.c_str(), r.path.c_str(), r.vid_pid.c_str(),
                  rate.c_str(), r.name.c_str(), note.c_str());
    }
  });
}

}  // namespace foveal::cmd

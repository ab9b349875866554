// foveal outputs: where frames can go. The DRM/KMS connectors of every card (what
// `foveald --drm` chooses among, marking its choice for the display model) and the
// monitors the window system shows (what `foveald --window --monitor` names).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>

#include "commands.hpp"
#include "foveal/core/display_model.hpp"
#include "foveal/render/drm_output.hpp"
#include "foveal/render/window.hpp"
#include "foveal/runtime/cli.hpp"

namespace foveal::cmd {

void add_outputs(CLI::App& app, int& exit_code) {
  struct Args {
    std::string display;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("outputs", "List DRM/KMS connectors (direct mode) and window-system monitors");
  sub->add_option("--display", a->display, "Display model whose output to look for: a name under data/display or a JSON file (default: htc_vive_pro_eye)");
  sub->add_flag("--json", a->json, "Print the list as JSON");
  sub->callback([a, &exit_code] {
    DisplayModel model = DisplayModel::vive_pro_eye();
    if (!a->display.empty()) {
      auto m = DisplayModel::load(display_model_path(a->display));
      if (!m) {
        exit_code = cli::report(m.error());
        return;
      }
      model = *m;
    }
    const render::KmsWanted wanted = render::headset_output(model);

    nlohmann::json cards = nlohmann::json::array();
    std::string direct;  // "card connector mode" direct mode would take
    const std::vector<render::DrmDeviceInfo> devices = render::DrmOutput::list_devices();
    for (const render::DrmDeviceInfo& d : devices) {
      nlohmann::json conns = nlohmann::json::array();
      for (const auto& c : d.connectors) conns.push_back(render::connector_json(c));
      nlohmann::json card = {{"device", d.path}, {"driver", d.driver}, {"connectors", conns}};
      if (!d.error.empty()) card["error"] = d.error;
      if (auto ch = render::choose_output(d.connectors, wanted); ch && direct.empty() && d.error.empty()) {
        const auto& m = d.connectors[ch->connector].modes[ch->mode];
        char b[160];
        std::snprintf(b, sizeof b, "%s %s %dx%d@%.2f", d.path.c_str(), d.connectors[ch->connector].name.c_str(),
                      m.width, m.height, m.refresh_hz);
        direct = b;
      }
      cards.push_back(card);
    }
    auto monitors = render::Window::monitors();
    const nlohmann::json mons = monitors ? nlohmann::json(*monitors) : nlohmann::json(nullptr);
    if (a->json) {
      cli::print_json({{"drm", cards},
                       {"direct_mode", direct.empty() ? nlohmann::json(nullptr) : nlohmann::json(direct)},
                       {"monitors", mons},
                       {"monitors_error", monitors ? nlohmann::json(nullptr) : nlohmann::json(monitors.error().message)}});
      return;
    }
    if (devices.empty()) std::printf("DRM: no /dev/dri/card* devices\n");
    for (const render::DrmDeviceInfo& d : devices) {
      std::printf("%s (%s)%s\n", d.path.c_str(), d.driver.empty() ? "?" : d.driver.c_str(),
                  d.error.empty() ? "" : (": " + d.error).c_str());
      for (const auto& c : d.connectors) std::printf("  %s\n", render::describe(c).c_str());
    }
    std::printf("direct mode (%dx%d for %s): %s\n", wanted.width, wanted.height, model.name.c_str(),
                direct.empty() ? "no matching connector" : direct.c_str());
    if (monitors) {
      std::printf("window-system monitors:%s\n", monitors->empty() ? " none" : "");
      for (const auto& m : *monitors) std::printf("  %s\n", m.c_str());
    } else {
      std::printf("window-system monitors: none (%s)\n", monitors.error().message.c_str());
    }
  });
}

}  // namespace foveal::cmd

#include "service_options.hpp"

#include <cstdlib>

#include "foveal/runtime/daemon_config.hpp"
#include "foveal/runtime/profile.hpp"

namespace foveal::daemon {

std::string default_config_path() { return daemon_config_path(ProfileStore::user().root()); }

std::string default_service_out() {
  if (const char* x = std::getenv("XDG_STATE_HOME"); x && *x) return std::string(x) + "/foveal";
  const char* home = std::getenv("HOME");
  return std::string(home && *home ? home : ".") + "/.local/state/foveal";
}

namespace {

/// on/off keys become flags; every other key is `--key value`.
Status append_entry(const std::string& key, const std::string& value, const std::string& where,
                    std::vector<std::string>& args) {
  if (key == "render" || key == "drm" || key == "trace") {
    if (value != "on" && value != "off") return bad_input(where + ": " + key + ": on or off, not '" + value + "'");
    if (key == "render") args.push_back(value == "on" ? "--render" : "--no-render");
    if (key == "trace") args.push_back(value == "on" ? "--trace" : "--no-trace");
    if (key == "drm" && value == "on") args.push_back("--drm");
    return {};
  }
  args.push_back("--" + key);
  args.push_back(value);
  return {};
}

}  // namespace

Result<std::vector<std::string>> service_arguments(const std::string& path, bool service,
                                                   const std::function<bool(const std::string&)>& given) {
  auto config = DaemonConfig::load(path);
  if (!config) return config.error();
  std::vector<std::string> args;
  for (const auto& [key, value] : config->entries()) {
    if (given("--" + key)) continue;  // the command line wins
    if (auto s = append_entry(key, value, path, args); !s) return s.error();
  }
  if (service) {
    auto unset = [&](const std::string& key) { return !given("--" + key) && !config->get(key); };
    if (unset("source")) args.insert(args.end(), {"--source", "auto"});
    if (unset("head")) args.insert(args.end(), {"--head", "auto"});
    if (unset("render")) args.push_back("--no-render");
    if (unset("trace")) args.push_back("--no-trace");
    if (unset("out")) args.insert(args.end(), {"--out", default_service_out()});
  }
  return args;
}

std::string config_text(const Options& o) {
  std::string s = "# foveald's options file keys as this run uses them; `# key` lines: foveald's default\n";
  auto line = [&](const char* key, const std::string& value) {
    s += value.empty() ? std::string("# ") + key + "\n" : std::string(key) + " = " + value + "\n";
  };
  line("source", o.source.empty() && !o.replay.empty() ? "replay:" + o.replay : o.source);
  line("head", o.head);
  line("profile", o.profile);
  line("quality", o.quality);
  line("display", o.display);
  line("out", o.out);
  line("render", o.render ? "on" : "off");
  line("trace", o.trace ? "on" : "off");
  line("predict", o.predict);
  line("latch", o.latch);
  line("pacing", o.pacing);
  line("monitor", o.monitor);
  line("drm", o.drm ? "on" : "off");
  line("connector", o.connector);
  line("mode", o.mode);
  line("control", o.control);
  line("realtime", o.rt_priority > 0 ? std::to_string(o.rt_priority) : "");
  return s;
}

}  // namespace foveal::daemon

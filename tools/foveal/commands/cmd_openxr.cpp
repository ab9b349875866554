// foveal openxr: whether OpenXR applications get foveald's gaze, and if not, why
// (docs/openxr.md). It reads the loader's files and the environment as an app started
// from this shell would, asks the runtime for its own eye gaze (in a child process,
// with a time limit), and asks foveald.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <string>

#include "commands.hpp"
#include "foveal/openxr/status.hpp"
#include "foveal/runtime/cli.hpp"

namespace foveal::cmd {

namespace {

nlohmann::json to_json(const openxr::OpenXRStatus& s) {
  nlohmann::json layers = nlohmann::json::array();
  for (const auto& l : s.layers)
    layers.push_back({{"manifest", l.path},
                      {"kind", l.implicit ? "implicit" : "explicit"},
                      {"library", l.library},
                      {"library_exists", l.library_exists},
                      {"disable_environment", l.disable_environment},
                      {"enable_environment", l.enable_environment},
                      {"problem", l.problem}});
  const auto& g = s.runtime_gaze;
  return {{"layer", {{"manifests", layers}, {"enabled", s.enabled}, {"why", s.enabled_reason}, {"gaze_mode", s.gaze_mode}}},
          {"runtime",
           {{"manifest", s.runtime.manifest},
            {"chosen_by", s.runtime.chosen_by},
            {"library", s.runtime.library},
            {"library_exists", s.runtime.library_exists},
            {"problem", s.runtime.problem},
            {"probed", g.probed},
            {"failed", g.runtime_failed},
            {"message", g.message},
            {"name", g.runtime_name},
            {"system", g.system_name},
            {"lists_eye_gaze_interaction", g.lists_eye_gaze_interaction},
            {"own_eye_gaze", g.supports_eye_gaze_interaction}}},
          {"foveald", {{"serving", s.foveald_serving}, {"message", s.foveald_message}}}};
}

/// Who answers an app's eye gaze, in one sentence. A runtime that is missing or broken
/// comes first: without one no OpenXR app starts, whatever the layer does.
std::string verdict(const openxr::OpenXRStatus& s) {
  const auto& g = s.runtime_gaze;
  if (s.runtime.manifest.empty() && !g.probed)
    return "no OpenXR runtime found: OpenXR apps cannot start here, with or without foveal's layer (install one, "
           "such as Monado, and make it the active runtime, or set XR_RUNTIME_JSON)";
  if (!s.runtime.problem.empty()) return "the runtime's manifest is unusable: OpenXR apps cannot start here until it is fixed";
  if (!s.runtime.library_exists && !g.probed) return "the runtime's library is missing: OpenXR apps cannot start here";
  if (g.runtime_failed) return "the runtime failed when probed (" + g.message + "): OpenXR apps are likely to fail the same way";
  if (!s.enabled) return "apps get no gaze from foveal: the layer is not on";
  if (s.gaze_mode == "runtime") return "FOVEAL_OPENXR_GAZE=runtime: the layer passes everything to the runtime";
  if (g.supports_eye_gaze_interaction && s.gaze_mode != "foveal")
    return "the runtime's own eye tracker answers (FOVEAL_OPENXR_GAZE=foveal would serve foveald's)";
  return s.foveald_serving ? "apps get foveald's gaze" : "apps see eye gaze listed but inactive until foveald serves";
}

/// The probe's output to show: all of it with -v; its last lines when the probe failed
/// (they usually say why); nothing otherwise, as loaders and runtimes are chatty.
std::string probe_log_shown(const openxr::RuntimeGaze& g, bool verbose) {
  constexpr int kTailLines = 20;
  if (verbose) return g.log;
  if (g.probed || g.log.empty()) return "";
  std::size_t from = g.log.size();
  if (from > 0 && g.log[from - 1] == '\n') --from;
  for (int lines = 0; from > 0; --from)
    if (g.log[from - 1] == '\n' && ++lines == kTailLines) break;
  return g.log.substr(from);
}

}  // namespace

void add_openxr(CLI::App& app, int& exit_code) {
  struct Args {
    bool json = false, no_probe = false, verbose = false;
    double probe_timeout_s = openxr::kDefaultProbeTimeoutS;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("openxr", "Whether OpenXR applications get foveald's gaze through foveal's layer");
  sub->add_flag("--no-probe", a->no_probe, "Do not load the runtime to ask for its own eye gaze");
  sub->add_option("--probe-timeout", a->probe_timeout_s, "Seconds to wait for the runtime's answer before stopping the probe")
      ->check(CLI::Range(0.1, 600.0))
      ->capture_default_str();
  sub->add_flag("-v,--verbose", a->verbose, "Show what the loader and the runtime printed during the probe");
  sub->add_flag("--json", a->json, "Print the status as JSON");
  sub->callback([a, &exit_code] {
    const openxr::OpenXRStatus s = openxr::openxr_status(!a->no_probe, a->probe_timeout_s);
    exit_code = cli::kExitOk;
    const std::string log = probe_log_shown(s.runtime_gaze, a->verbose);
    if (a->json) {
      nlohmann::json j = to_json(s);
      j["runtime"]["probe_log"] = log;
      j["verdict"] = verdict(s);
      cli::print_json(j);
      return;
    }
    std::printf("layer:   %s (%s)\n", s.enabled ? "on" : "off", s.enabled_reason.c_str());
    for (const auto& l : s.layers) {
      if (!l.problem.empty()) std::printf("         %s, broken: %s\n", l.implicit ? "implicit" : "explicit", l.problem.c_str());
      else
        std::printf("         %s %s -> %s%s\n", l.implicit ? "implicit" : "explicit", l.path.c_str(), l.library.c_str(),
                    l.library_exists ? "" : " (missing)");
    }
    std::printf("         FOVEAL_OPENXR_GAZE=%s\n", s.gaze_mode.c_str());
    if (s.runtime.manifest.empty()) std::printf("runtime: none found (XR_RUNTIME_JSON unset, no active_runtime.json)\n");
    else {
      std::printf("runtime: %s, chosen by %s\n", s.runtime.manifest.c_str(), s.runtime.chosen_by.c_str());
      if (!s.runtime.problem.empty()) std::printf("         unusable: %s\n", s.runtime.problem.c_str());
      else if (!s.runtime.library_exists) std::printf("         its library is missing: %s\n", s.runtime.library.c_str());
    }
    const auto& g = s.runtime_gaze;
    if (g.probed)
      std::printf("         %s, %s: own eye gaze %s\n", g.runtime_name.c_str(), g.system_name.c_str(),
                  g.supports_eye_gaze_interaction ? "yes" : g.lists_eye_gaze_interaction ? "no (listed, no eye tracker)" : "no");
    else if (!a->no_probe)
      std::printf("         probe: %s\n", g.message.c_str());
    if (!log.empty())
      std::printf("         the probe's output%s:\n%s%s", a->verbose ? "" : " (its end)", log.c_str(),
                  log.back() == '\n' ? "" : "\n");
    std::printf("foveald: %s\n", s.foveald_serving ? s.foveald_message.c_str() : ("not serving: " + s.foveald_message).c_str());
    std::printf("=> %s\n", verdict(s).c_str());
  });
}

}  // namespace foveal::cmd

#include "foveal/openxr/status.hpp"

#include <foveal/client.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "foveal/core/json_file.hpp"

namespace foveal::openxr {

namespace {

constexpr const char* kLayerName = "XR_APILAYER_FOVEAL_gaze";
constexpr const char* kLayerFile = "XrApiLayer_foveal_gaze.json";

std::string env(const char* name, const std::string& fallback = "") {
  const char* v = std::getenv(name);
  return v && *v ? v : fallback;
}

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> out;
  std::istringstream in(list);
  for (std::string item; std::getline(in, item, ':');)
    if (!item.empty()) out.push_back(item);
  return out;
}

/// The loader's configuration folders on Linux, in its order: XDG_CONFIG_HOME,
/// XDG_CONFIG_DIRS, /etc, then (for layers) XDG_DATA_HOME and XDG_DATA_DIRS.
std::vector<std::string> search_roots(bool with_data) {
  const std::string home = env("HOME");
  std::vector<std::string> roots = {env("XDG_CONFIG_HOME", home + "/.config")};
  for (const auto& d : split(env("XDG_CONFIG_DIRS", "/etc/xdg"))) roots.push_back(d);
  roots.push_back("/etc");
  if (with_data) {
    roots.push_back(env("XDG_DATA_HOME", home + "/.local/share"));
    for (const auto& d : split(env("XDG_DATA_DIRS", "/usr/local/share:/usr/share"))) roots.push_back(d);
  }
  return roots;
}

/// A manifest's library as the loader resolves it: a relative path with a slash is
/// relative to the manifest's folder; a bare name is left to the dynamic linker.
std::string resolve_library(const std::string& manifest, const std::string& lib) {
  if (lib.empty() || lib.front() == '/' || lib.find('/') == std::string::npos) return lib;
  return (std::filesystem::path(manifest).parent_path() / lib).lexically_normal().string();
}

bool exists(const std::string& lib) {
  std::error_code ec;
  return lib.find('/') == std::string::npos || std::filesystem::is_regular_file(lib, ec);
}

void add_layer(OpenXRStatus& s, const std::string& path, bool implicit) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return;
  auto j = read_json_file(path, "OpenXR layer manifest", JsonLimits{1 << 20, 16});
  if (!j || !j->is_object() || !j->contains("api_layer") || !(*j)["api_layer"].is_object()) return;
  const auto& l = (*j)["api_layer"];
  if (l.value("name", "") != kLayerName) return;
  LayerManifest m;
  m.path = path;
  m.implicit = implicit;
  m.library = resolve_library(path, l.value("library_path", ""));
  m.library_exists = exists(m.library);
  m.disable_environment = l.value("disable_environment", "");
  m.enable_environment = l.value("enable_environment", "");
  s.layers.push_back(m);
}

void find_layers(OpenXRStatus& s) {
  for (const auto& root : search_roots(true)) {
    add_layer(s, root + "/openxr/1/api_layers/implicit.d/" + kLayerFile, true);
    add_layer(s, root + "/openxr/1/api_layers/explicit.d/" + kLayerFile, false);
  }
  for (const auto& dir : split(env("XR_API_LAYER_PATH"))) add_layer(s, dir + "/" + kLayerFile, false);
  // The loader takes the first implicit manifest of a name; the environment decides.
  for (const LayerManifest& m : s.layers) {
    if (!m.implicit) continue;
    if (!m.library_exists) s.enabled_reason = m.path + " names a library that is not there: " + m.library;
    else if (!m.disable_environment.empty() && !env(m.disable_environment.c_str()).empty())
      s.enabled_reason = m.disable_environment + " is set: the layer is off";
    else if (!m.enable_environment.empty() && env(m.enable_environment.c_str()).empty())
      s.enabled_reason = "opt-in build: set " + m.enable_environment + "=1 to turn the layer on";
    else {
      s.enabled = true;
      s.enabled_reason = "implicit layer " + m.path;
    }
    return;
  }
  const std::string enable = env("XR_ENABLE_API_LAYERS");
  for (const auto& name : split(enable))
    if (name == kLayerName && !s.layers.empty()) {
      s.enabled = true;
      s.enabled_reason = "XR_ENABLE_API_LAYERS names it";
      return;
    }
  s.enabled_reason = s.layers.empty() ? "no manifest of the layer where the loader looks (is foveal installed?)"
                                      : "installed as an explicit layer only: name it in XR_ENABLE_API_LAYERS";
}

void find_runtime(OpenXRStatus& s) {
  RuntimeChoice& r = s.runtime;
  if (std::string j = env("XR_RUNTIME_JSON"); !j.empty()) {
    r.manifest = j;
    r.chosen_by = "XR_RUNTIME_JSON";
  } else {
    for (const auto& root : search_roots(false)) {
      for (const char* name : {"active_runtime.x86_64.json", "active_runtime.json"}) {
        const std::string p = root + "/openxr/1/" + name;
        std::error_code ec;
        if (std::filesystem::exists(p, ec)) {
          r.manifest = p;
          r.chosen_by = "the active_runtime.json search (" + p + ")";
          break;
        }
      }
      if (!r.manifest.empty()) break;
    }
  }
  if (r.manifest.empty()) return;
  auto j = read_json_file(r.manifest, "OpenXR runtime manifest", JsonLimits{1 << 20, 16});
  if (j && j->is_object() && j->contains("runtime") && (*j)["runtime"].is_object())
    r.library = resolve_library(r.manifest, (*j)["runtime"].value("library_path", ""));
  r.library_exists = !r.library.empty() && exists(r.library);
}

void ask_foveald(OpenXRStatus& s) {
  foveal_error err{};
  foveal_client* c = foveal_client_open(nullptr, &err);
  if (!c) {
    s.foveald_message = err.message;
    return;
  }
  foveal_fovea f{};
  foveal_view v{};
  const int rc = foveal_client_read(c, &f);
  const int rv = foveal_client_view(c, &v);
  s.foveald_serving = rc == FOVEAL_OK && rv == FOVEAL_OK;
  s.foveald_message = rc != FOVEAL_OK ? foveal_error_message(rc)
                      : rv != FOVEAL_OK ? std::string("an older foveald: its block has no view for the layer")
                                        : "publishing gaze (sample " + std::to_string(f.frame) + ")";
  foveal_client_close(c);
}

}  // namespace

RuntimeGaze probe_runtime_gaze();  // runtime_probe.cpp

OpenXRStatus openxr_status(bool probe_runtime) {
  OpenXRStatus s;
  find_layers(s);
  s.gaze_mode = env("FOVEAL_OPENXR_GAZE", "auto");
  find_runtime(s);
  if (probe_runtime) s.runtime_gaze = probe_runtime_gaze();
  ask_foveald(s);
  return s;
}

}  // namespace foveal::openxr

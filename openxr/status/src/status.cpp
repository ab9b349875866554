#include "foveal/openxr/status.hpp"

#include <foveal/client.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "foveal/core/json_file.hpp"
#include "probe.hpp"

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

/// A manifest's string field `section.key`: "" when absent; another type is the
/// manifest's problem, named with the file and the field (the loader would skip it).
bool string_field(const nlohmann::json& section, const std::string& path, const std::string& section_name,
                  const char* key, std::string& out, std::string& problem) {
  auto it = section.find(key);
  if (it == section.end()) return true;
  if (it->is_string()) {
    out = it->get<std::string>();
    return true;
  }
  const char* article = it->is_array() || it->is_object() ? "an " : it->is_null() ? "" : "a ";
  problem = path + ": " + section_name + "." + key + " is " + article + it->type_name() + ", not a string";
  return false;
}

/// The manifest's object `section`, or null with the problem said.
const nlohmann::json* manifest_section(const Result<nlohmann::json>& j, const std::string& path, const char* section,
                                       std::string& problem) {
  if (!j) {
    problem = j.error().message;
    return nullptr;
  }
  if (!j->is_object() || !j->contains(section) || !(*j)[section].is_object()) {
    problem = path + ": no \"" + std::string(section) + "\" object";
    return nullptr;
  }
  return &(*j)[section];
}

void add_layer(OpenXRStatus& s, const std::string& path, bool implicit) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return;
  LayerManifest m;
  m.path = path;
  m.implicit = implicit;
  // A file under the layer's own name that the loader cannot use is listed as broken.
  const auto j = read_json_file(path, "OpenXR layer manifest", JsonLimits{1 << 20, 16});
  const nlohmann::json* l = manifest_section(j, path, "api_layer", m.problem);
  if (!l) {
    s.layers.push_back(m);
    return;
  }
  std::string name, library;
  if (!string_field(*l, path, "api_layer", "name", name, m.problem)) {
    s.layers.push_back(m);
    return;
  }
  if (name.empty()) m.problem = path + ": api_layer.name is missing";
  else if (name != kLayerName) return;  // another layer's manifest under this name
  if (m.problem.empty() && string_field(*l, path, "api_layer", "library_path", library, m.problem) &&
      string_field(*l, path, "api_layer", "disable_environment", m.disable_environment, m.problem) &&
      string_field(*l, path, "api_layer", "enable_environment", m.enable_environment, m.problem) && library.empty())
    m.problem = path + ": api_layer.library_path is missing";
  m.library = resolve_library(path, library);
  m.library_exists = m.problem.empty() && exists(m.library);
  s.layers.push_back(m);
}

void find_layers(OpenXRStatus& s) {
  for (const auto& root : search_roots(true)) {
    add_layer(s, root + "/openxr/1/api_layers/implicit.d/" + kLayerFile, true);
    add_layer(s, root + "/openxr/1/api_layers/explicit.d/" + kLayerFile, false);
  }
  for (const auto& dir : split(env("XR_API_LAYER_PATH"))) add_layer(s, dir + "/" + kLayerFile, false);
  // The loader takes the first usable implicit manifest of a name; the environment decides.
  for (const LayerManifest& m : s.layers) {
    if (!m.implicit || !m.problem.empty()) continue;
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
  const bool usable = std::any_of(s.layers.begin(), s.layers.end(), [](const LayerManifest& m) { return m.problem.empty(); });
  for (const auto& name : split(enable))
    if (name == kLayerName && usable) {
      s.enabled = true;
      s.enabled_reason = "XR_ENABLE_API_LAYERS names it";
      return;
    }
  if (s.layers.empty()) s.enabled_reason = "no manifest of the layer where the loader looks (is foveal installed?)";
  else if (!usable) s.enabled_reason = "every manifest of the layer is broken; the first: " + s.layers.front().problem;
  else s.enabled_reason = "installed as an explicit layer only: name it in XR_ENABLE_API_LAYERS";
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
  // Read without blocking (a FIFO is refused, not waited on), every field type-checked.
  const auto j = read_json_file(r.manifest, "OpenXR runtime manifest", JsonLimits{1 << 20, 16});
  const nlohmann::json* rt = manifest_section(j, r.manifest, "runtime", r.problem);
  std::string library;
  if (rt && string_field(*rt, r.manifest, "runtime", "library_path", library, r.problem) && library.empty())
    r.problem = r.manifest + ": runtime.library_path is missing";
  if (!r.problem.empty()) return;
  r.library = resolve_library(r.manifest, library);
  r.library_exists = exists(r.library);
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

OpenXRStatus openxr_status(bool probe_runtime, double probe_timeout_s) {
  OpenXRStatus s;
  find_layers(s);
  s.gaze_mode = env("FOVEAL_OPENXR_GAZE", "auto");
  find_runtime(s);
  if (probe_runtime && !s.runtime.problem.empty())
    s.runtime_gaze.message = "the runtime's manifest is unusable (see above)";  // the loader would fail or wait on it
  else if (probe_runtime)
    s.runtime_gaze = probe_runtime_in_child(probe_timeout_s);
  ask_foveald(s);
  return s;
}

}  // namespace foveal::openxr

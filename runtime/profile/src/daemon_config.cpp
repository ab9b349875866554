#include "foveal/runtime/daemon_config.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>

#include "foveal/core/read_file.hpp"

namespace foveal {

namespace {

// The service's keys: where the gaze and the head come from, the user's settings, where
// the outputs go, and whether (and how) it renders. Per-run options (replay windows,
// frame counts, scenes) stay on the command line.
constexpr std::array kKeys = {
    DaemonConfigKey{"source", "gaze source: auto (the default for the service), hid, psvr2, replay:PATH ..."},
    DaemonConfigKey{"head", "camera: auto (the default for the service), static, psvr2, vive[:PATH] ..."},
    DaemonConfigKey{"profile", "user profile (default: the active one)"},
    DaemonConfigKey{"quality", "jod:T or off, replacing the profile's quality"},
    DaemonConfigKey{"display", "display model: a name under data/display or a JSON file (default: the profile's)"},
    DaemonConfigKey{"out", "output directory"},
    DaemonConfigKey{"render", "on or off: run the compositor (off for the service unless set)"},
    DaemonConfigKey{"trace", "on or off: write trace.csv at exit (off for the service unless set: ~45 MB an hour)"},
    DaemonConfigKey{"predict", "on or off: the fovea predicted to display time"},
    DaemonConfigKey{"latch", "late or early: when a frame reads the fovea"},
    DaemonConfigKey{"pacing", "jit or asap"},
    DaemonConfigKey{"monitor", "window mode: fullscreen on this monitor (auto: the headset's)"},
    DaemonConfigKey{"drm", "on or off: direct mode on a DRM/KMS connector"},
    DaemonConfigKey{"connector", "direct mode: connector name"},
    DaemonConfigKey{"mode", "direct mode: WxH or WxH@HZ"},
    DaemonConfigKey{"control", "control socket path"},
    DaemonConfigKey{"realtime", "SCHED_FIFO priority of the gaze thread, 1-99 (needs CAP_SYS_NICE)"},
};

bool known(std::string_view key) {
  return std::any_of(kKeys.begin(), kKeys.end(), [&](const DaemonConfigKey& k) { return key == k.name; });
}

std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

std::string key_list() {
  std::string s;
  for (const auto& k : kKeys) s += (s.empty() ? "" : ", ") + std::string(k.name);
  return s;
}

}  // namespace

std::span<const DaemonConfigKey> daemon_config_keys() { return kKeys; }

Result<DaemonConfig> DaemonConfig::parse(std::string_view text, const std::string& where) {
  DaemonConfig c;
  int line_no = 0;
  while (!text.empty()) {
    const std::size_t nl = text.find('\n');
    const std::string_view line = trim(text.substr(0, nl));
    text = nl == std::string_view::npos ? std::string_view{} : text.substr(nl + 1);
    ++line_no;
    if (line.empty() || line.front() == '#') continue;
    const std::string at = where + ":" + std::to_string(line_no) + ": ";
    const std::size_t eq = line.find('=');
    if (eq == std::string_view::npos) return bad_input(at + "expected `key = value`, got '" + std::string(line.substr(0, 80)) + "'");
    const std::string key(trim(line.substr(0, eq)));
    const std::string value(trim(line.substr(eq + 1)));
    if (!known(key)) return bad_input(at + "unknown key '" + key.substr(0, 80) + "' (keys: " + key_list() + ")");
    if (value.empty()) return bad_input(at + key + ": no value");
    if (c.get(key)) return bad_input(at + key + ": given twice");
    c.entries_.emplace_back(key, value);
  }
  return c;
}

Result<DaemonConfig> DaemonConfig::load(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 && errno == ENOENT) return DaemonConfig{};
  // A FIFO or a device is refused without blocking on it (read_file.hpp).
  auto text = read_regular_file(path, 1 << 20, "foveald's options file");
  if (!text) return text.error();
  return parse(*text, path);
}

const std::string* DaemonConfig::get(const std::string& key) const {
  for (const auto& [k, v] : entries_)
    if (k == key) return &v;
  return nullptr;
}

Status DaemonConfig::set(const std::string& key, const std::string& value) {
  if (!known(key)) return bad_input("unknown key '" + key + "' (keys: " + key_list() + ")");
  const std::string v(trim(value));
  if (v.empty()) return bad_input(key + ": no value");
  if (v.find_first_of("\n\r") != std::string::npos) return bad_input(key + ": the value has a line break");
  for (auto& [k, old] : entries_)
    if (k == key) {
      old = v;
      return {};
    }
  entries_.emplace_back(key, v);
  return {};
}

bool DaemonConfig::unset(const std::string& key) {
  const auto it = std::find_if(entries_.begin(), entries_.end(), [&](const auto& e) { return e.first == key; });
  if (it == entries_.end()) return false;
  entries_.erase(it);
  return true;
}

std::string DaemonConfig::text() const {
  std::string s = "# foveald's options for the user service (docs/daemon.md, \"Service\")\n";
  for (const auto& [k, v] : entries_) s += k + " = " + v + "\n";
  return s;
}

std::string daemon_config_path(const std::string& config_root) { return config_root + "/foveald.conf"; }

}  // namespace foveal

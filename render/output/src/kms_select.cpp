#include "foveal/render/kms_select.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace foveal::render {

std::optional<EdidIdentity> parse_edid_identity(std::span<const std::uint8_t> e) {
  static constexpr std::uint8_t kHeader[8] = {0x00, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x00};
  if (e.size() < 128) return std::nullopt;
  for (int i = 0; i < 8; ++i)
    if (e[i] != kHeader[i]) return std::nullopt;
  EdidIdentity id;
  // Manufacturer: three 5-bit letters, big-endian, 1 = 'A'.
  const unsigned m = (unsigned(e[8]) << 8) | e[9];
  for (int shift : {10, 5, 0}) {
    const unsigned letter = (m >> shift) & 0x1f;
    id.vendor += (letter >= 1 && letter <= 26) ? char('A' + letter - 1) : '?';
  }
  id.product = static_cast<std::uint16_t>(e[10] | (e[11] << 8));
  // Four 18-byte descriptors; a display descriptor starts with 0,0 and has its tag at 3.
  for (std::size_t d = 54; d + 18 <= 126; d += 18) {
    if (e[d] != 0 || e[d + 1] != 0 || e[d + 3] != 0xfc) continue;
    for (std::size_t i = d + 5; i < d + 18 && e[i] != 0x0a; ++i)
      if (e[i] >= 0x20 && e[i] < 0x7f) id.name += char(e[i]);
    while (!id.name.empty() && id.name.back() == ' ') id.name.pop_back();
  }
  return id;
}

namespace {

std::string mode_text(const KmsMode& m) {
  char b[48];
  std::snprintf(b, sizeof b, "%dx%d@%.2f%s", m.width, m.height, m.refresh_hz, m.preferred ? "*" : "");
  return b;
}

std::string list_all(const std::vector<KmsConnector>& cs) {
  if (cs.empty()) return " (the device has no connectors)";
  std::string s;
  for (const auto& c : cs) s += "\n  " + describe(c);
  return s;
}

// The mode of the wanted size nearest the wanted rate; without a rate the preferred
// one, else the fastest.
std::optional<std::size_t> pick_mode(const KmsConnector& c, const KmsWanted& w) {
  std::optional<std::size_t> best;
  auto better = [&](const KmsMode& a, const KmsMode& b) {
    if (w.refresh_hz > 0) return std::fabs(a.refresh_hz - w.refresh_hz) < std::fabs(b.refresh_hz - w.refresh_hz);
    if (a.preferred != b.preferred) return a.preferred;
    return a.refresh_hz > b.refresh_hz;
  };
  for (std::size_t i = 0; i < c.modes.size(); ++i) {
    const KmsMode& m = c.modes[i];
    if (m.width != w.width || m.height != w.height) continue;
    if (!best || better(m, c.modes[*best])) best = i;
  }
  return best;
}

}  // namespace

KmsWanted headset_output(const DisplayModel& model) {
  KmsWanted w;
  w.width = model.output_width();
  w.height = model.output_height();
  w.refresh_hz = model.refresh_hz;
  w.edid_vendor = model.edid_vendor;
  return w;
}

nlohmann::json connector_json(const KmsConnector& c) {
  nlohmann::json modes = nlohmann::json::array();
  for (const auto& m : c.modes)
    modes.push_back({{"width", m.width}, {"height", m.height}, {"refresh_hz", m.refresh_hz}, {"preferred", m.preferred}});
  nlohmann::json edid = nullptr;
  if (!c.edid_vendor.empty()) edid = {{"vendor", c.edid_vendor}, {"product", c.edid_product}, {"name", c.edid_name}};
  return {{"name", c.name}, {"connected", c.connected}, {"non_desktop", c.non_desktop}, {"edid", edid}, {"modes", modes}};
}

std::string describe(const KmsConnector& c) {
  std::string s = c.name + (c.connected ? " connected" : " disconnected");
  if (c.non_desktop) s += " non-desktop";
  if (!c.edid_vendor.empty()) {
    char b[16];
    std::snprintf(b, sizeof b, ":%04x", c.edid_product);
    s += " EDID " + c.edid_vendor + b;
    if (!c.edid_name.empty()) s += " '" + c.edid_name + "'";
  }
  if (!c.modes.empty()) {
    s += " modes";
    for (const auto& m : c.modes) s += " " + mode_text(m);
  }
  return s;
}

Result<KmsChoice> choose_output(const std::vector<KmsConnector>& cs, const KmsWanted& w) {
  char size[32];
  std::snprintf(size, sizeof size, "%dx%d", w.width, w.height);
  if (!w.connector.empty()) {
    for (std::size_t i = 0; i < cs.size(); ++i) {
      if (cs[i].name != w.connector) continue;
      if (!cs[i].connected) return bad_input("connector " + w.connector + " is disconnected:" + list_all(cs));
      auto m = pick_mode(cs[i], w);
      if (!m) return bad_input("connector " + w.connector + " has no " + size + " mode:" + list_all(cs));
      return KmsChoice{i, *m};
    }
    return bad_input("no connector named " + w.connector + ":" + list_all(cs));
  }
  std::optional<KmsChoice> any;
  for (std::size_t i = 0; i < cs.size(); ++i) {
    if (!cs[i].connected) continue;
    auto m = pick_mode(cs[i], w);
    if (!m) continue;
    const bool headset = cs[i].non_desktop || (!w.edid_vendor.empty() && cs[i].edid_vendor == w.edid_vendor);
    if (headset) return KmsChoice{i, *m};
    if (!any) any = KmsChoice{i, *m};
  }
  if (any) return *any;
  return bad_input(std::string("no connected connector offers a ") + size + " mode (the display model's size; "
                   "--mode picks another):" + list_all(cs));
}

Status parse_mode(const std::string& text, KmsWanted& w) {
  int width = 0, height = 0, used = 0;
  double hz = 0;
  const char* s = text.c_str();
  if (std::sscanf(s, "%dx%d%n", &width, &height, &used) != 2 || width < 1 || height < 1 || width > 16384 ||
      height > 16384)
    return bad_input("--mode '" + text + "': expected WxH or WxH@HZ, e.g. 2880x1600@90");
  if (s[used] == '@') {
    char* end = nullptr;
    hz = std::strtod(s + used + 1, &end);
    if (end == s + used + 1 || *end != '\0' || !(hz > 0 && hz <= 1000))
      return bad_input("--mode '" + text + "': the rate after @ must be a number of Hz in (0, 1000]");
  } else if (s[used] != '\0') {
    return bad_input("--mode '" + text + "': expected WxH or WxH@HZ, e.g. 2880x1600@90");
  }
  w.width = width;
  w.height = height;
  w.refresh_hz = hz;
  return {};
}

}  // namespace foveal::render

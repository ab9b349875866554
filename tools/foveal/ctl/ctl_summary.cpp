#include "ctl/ctl_summary.hpp"

#include <cstdio>

#include "foveal/core/shown_text.hpp"

namespace foveal::cmd {

namespace {

using nlohmann::json;

std::string num(const json& v, int decimals = 1) {
  if (!v.is_number()) return "?";
  char b[48];
  std::snprintf(b, sizeof b, "%.*f", decimals, v.get<double>());
  return b;
}

std::string text(const json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_string() ? it->get<std::string>() : std::string();
}

std::string levels(const json& s) {
  if (!s.is_object()) return "";
  return text(s, "dominant_eye") + " dominant, sigma " + shown_number(s.value("sigma_d", 0.0)) + "/" +
         shown_number(s.value("sigma_nd", 0.0));
}

}  // namespace

std::string status_line(const json& st) {
  std::string line = text(st, "state");
  auto part = [&](const std::string& p) {
    if (!p.empty()) line += (line.empty() ? "" : " · ") + p;
  };
  if (const auto src = st.find("source"); src != st.end() && src->is_object())
    part("source " + text(*src, "spec") + " " + text(*src, "state") + ", " + num(st.value("sample_rate_hz", json()), 0) +
         " Hz, " + std::to_string(st.value("samples", 0)) + " samples");
  if (st.contains("profile")) part("profile " + text(st, "profile") + ": " + levels(st.value("settings", json())));
  if (const auto r = st.find("render"); r != st.end() && r->is_object()) {
    std::string p = "render " + text(*r, "pipeline") + " " + text(*r, "method");
    if (const auto& size = r->value("size", json()); size.is_array() && size.size() == 2)
      p += " " + std::to_string(size[0].get<int>()) + "x" + std::to_string(size[1].get<int>());
    p += ", " + std::to_string(r->value("frames", 0)) + " frames";
    const json g = r->value("gaze_to_photon", json::object()).value("gaze_to_photon_ms", json::object());
    if (g.contains("p50")) p += ", gaze to photon p50 " + num(g["p50"]) + " ms";
    part(p);
  } else if (st.contains("render")) {
    part("no rendering");
  }
  if (st.contains("uptime_s")) part("up " + num(st["uptime_s"]) + " s");
  return line;
}

std::string fovea_line(const json& f) {
  std::string line;
  for (const char* eye : {"left", "right"}) {
    const json e = f.value(eye, json::object());
    line += std::string(line.empty() ? "" : ", ") + eye + " " + num(e.value("x_px", json())) + "," +
            num(e.value("y_px", json())) + " (" + text(e, "state") + ")";
  }
  if (const auto s = f.find("space"); s != f.end() && s->is_object())
    line += " · pixels of one eye's " + std::to_string(s->value("eye_width", 0)) + "x" +
            std::to_string(s->value("eye_height", 0)) + " viewport, origin " + text(*s, "origin");
  return line;
}

std::string change_line(const json& reply, const std::string& cmd) {
  return std::string(cmd == "use" ? "switched to" : "set") + " · foveald now uses profile " + text(reply, "profile") +
         ": " + levels(reply.value("settings", json())) + " · not saved: this lasts until foveald stops" +
         (cmd == "set" ? " (`foveal profile set` saves)" : "");
}

}  // namespace foveal::cmd

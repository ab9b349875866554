#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "foveal/core/json_file.hpp"
#include "foveal/core/shown_text.hpp"
#include "foveal/runtime/filter_config.hpp"
#include "foveal/runtime/profile.hpp"

namespace foveal {

namespace {

constexpr const char* kFormat = "foveal-profile v1";

Result<double> number(const nlohmann::json& v, const std::string& where, const std::string& key) {
  if (!v.is_number()) return bad_input(where + ": " + key + ": expected a number");
  const double d = v.get<double>();
  if (!std::isfinite(d)) return bad_input(where + ": " + key + ": must be finite");
  return d;
}

Result<std::optional<double>> number_or_auto(const nlohmann::json& v, const std::string& where, const std::string& key) {
  if (v.is_string() && v.get<std::string>() == "auto") return std::optional<double>{};
  auto d = number(v, where, key);
  if (!d) return bad_input(where + ": " + key + ": expected a number or \"auto\"");
  return std::optional<double>{*d};
}

Result<Eye> eye_from(const std::string& s, const std::string& where) {
  if (s == "left") return Eye::left;
  if (s == "right") return Eye::right;
  return bad_input(where + ": dominant_eye: '" + s + "' is not left or right");
}

constexpr const char* kQualityChannels[3] = {"left", "right", "binocular"};
constexpr std::pair<const char*, double ProfileGazeQuality::Channel::*> kQualityFields[] = {
    {"accuracy_deg", &ProfileGazeQuality::Channel::accuracy_deg},
    {"rms_s2s_deg", &ProfileGazeQuality::Channel::rms_s2s_deg},
    {"std_deg", &ProfileGazeQuality::Channel::std_deg},
    {"data_loss_pct", &ProfileGazeQuality::Channel::data_loss_pct}};

nlohmann::json quality_to_json(const ProfileGazeQuality& q) {
  nlohmann::json j = {{"source", q.source}, {"targets", q.targets}};
  for (std::size_t c = 0; c < 3; ++c)
    for (const auto& [key, field] : kQualityFields) {
      const double v = q.channels[c].*field;
      j[kQualityChannels[c]][key] = std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
    }
  return j;
}

Result<ProfileGazeQuality> quality_from_json(const nlohmann::json& j, const std::string& where) {
  const std::string at = where + ": gaze_quality";
  if (!j.is_object()) return bad_input(at + ": expected an object");
  ProfileGazeQuality q;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& k = it.key();
    const nlohmann::json& v = it.value();
    if (k == "source") {
      if (!v.is_string()) return bad_input(at + ": source: expected a string");
      q.source = v.get<std::string>();
      continue;
    }
    if (k == "targets") {
      if (!v.is_number_integer() || v.get<std::int64_t>() < 0) return bad_input(at + ": targets: expected a count >= 0");
      q.targets = static_cast<int>(std::min<std::int64_t>(v.get<std::int64_t>(), 1'000'000));
      continue;
    }
    std::size_t c = 0;
    while (c < 3 && k != kQualityChannels[c]) ++c;
    if (c == 3) return bad_input(at + ": unknown key '" + k + "'");
    if (!v.is_object()) return bad_input(at + "." + k + ": expected an object");
    for (auto f = v.begin(); f != v.end(); ++f) {
      const auto* field = std::find_if(std::begin(kQualityFields), std::end(kQualityFields),
                                       [&](const auto& kf) { return f.key() == kf.first; });
      if (field == std::end(kQualityFields)) return bad_input(at + "." + k + ": unknown key '" + f.key() + "'");
      if (f.value().is_null()) continue;  // not measurable
      auto d = number(f.value(), at + "." + k, f.key());
      if (!d) return d.error();
      // Data loss may dip below 0: a tracker faster than its nominal rate.
      if (*d < 0 && f.key() != "data_loss_pct") return bad_input(at + "." + k + ": " + f.key() + ": must be >= 0");
      q.channels[c].*(field->second) = *d;
    }
  }
  return q;
}

}  // namespace

Result<std::optional<double>> parse_quality(const std::string& spec, const std::string& where) {
  if (spec.empty() || spec == "off") return std::optional<double>{};
  const std::string bad = where + ": quality: '" + shown_text(spec, 40) + "' is not off or jod:T with T in (0, 10]";
  if (spec.rfind("jod:", 0) != 0 || spec.size() == 4) return bad_input(bad);
  char* end = nullptr;
  errno = 0;
  const double t = std::strtod(spec.c_str() + 4, &end);
  if (*end != '\0' || errno == ERANGE || !(t > 0 && t <= 10)) return bad_input(bad);
  return std::optional<double>{t};
}

bool valid_profile_name(const std::string& name) {
  if (name.empty() || name.size() > 64) return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_')) return false;
  return true;
}

nlohmann::json Profile::to_json() const {
  nlohmann::json j;
  j["format"] = kFormat;
  j["dominant_eye"] = eye_name(dominant_eye);
  j["sigma_d"] = sigma_d;
  j["sigma_nd"] = sigma_nd;
  j["f_x"] = f_x ? nlohmann::json(*f_x) : nlohmann::json("auto");
  j["f_y"] = f_y ? nlohmann::json(*f_y) : nlohmann::json("auto");
  j["ipd_mm"] = ipd_mm;
  j["display_model"] = display_model;
  j["filter"] = filter;
  if (gaze_quality) j["gaze_quality"] = quality_to_json(*gaze_quality);
  if (!quality.empty()) j["quality"] = quality;
  if (temporal) j["temporal"] = "on";
  return j;
}

Status Profile::validate(const std::string& where) const {
  if (!(sigma_d >= 1.0 && sigma_d <= 16.0)) return bad_input(where + ": sigma_d: must be in [1, 16]");
  if (!(sigma_nd >= 1.0 && sigma_nd <= 16.0)) return bad_input(where + ": sigma_nd: must be in [1, 16]");
  if (sigma_nd < sigma_d)
    return bad_input(where + ": sigma_nd (" + shown_number(sigma_nd) + ") must be >= sigma_d (" +
                     shown_number(sigma_d) + "): the non-dominant eye is foveated at least as much");
  for (const auto& [key, f] : {std::pair{"f_x", f_x}, std::pair{"f_y", f_y}})
    if (f && !(*f >= kMinRmfrF && *f <= kMaxRmfrF))
      return bad_input(where + ": " + key + ": " + shown_number(*f) + " is not in [" + shown_number(kMinRmfrF) + ", " +
                       shown_number(kMaxRmfrF) + "] (the range the compositor is tested at) or \"auto\"");
  if (!(ipd_mm > 40.0 && ipd_mm < 90.0)) return bad_input(where + ": ipd_mm: must be in (40, 90)");
  if (display_model.empty()) return bad_input(where + ": display_model: must not be empty");
  if (auto f = FilterConfig::from_json(filter, where); !f) return f.error();
  if (auto q = parse_quality(quality, where); !q) return q.error();
  return {};
}

Result<Profile> Profile::from_json(const nlohmann::json& j, const std::string& name, const std::string& where) {
  if (!j.is_object()) return bad_input(where + ": expected a JSON object");
  Profile p;
  p.name = name;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& k = it.key();
    const nlohmann::json& v = it.value();
    if (k == "format") {
      if (!v.is_string() || v.get<std::string>() != kFormat)
        return bad_input(where + ": format: expected \"" + std::string(kFormat) + "\"");
    } else if (k == "dominant_eye") {
      if (!v.is_string()) return bad_input(where + ": dominant_eye: expected \"left\" or \"right\"");
      auto e = eye_from(v.get<std::string>(), where);
      if (!e) return e.error();
      p.dominant_eye = *e;
    } else if (k == "sigma_d" || k == "sigma_nd" || k == "ipd_mm") {
      auto d = number(v, where, k);
      if (!d) return d.error();
      (k == "sigma_d" ? p.sigma_d : k == "sigma_nd" ? p.sigma_nd : p.ipd_mm) = *d;
    } else if (k == "f_x" || k == "f_y") {
      auto f = number_or_auto(v, where, k);
      if (!f) return f.error();
      (k == "f_x" ? p.f_x : p.f_y) = *f;
    } else if (k == "display_model") {
      if (!v.is_string()) return bad_input(where + ": display_model: expected a string");
      p.display_model = v.get<std::string>();
    } else if (k == "filter") {
      p.filter = v;
    } else if (k == "quality") {
      if (!v.is_string()) return bad_input(where + ": quality: expected a string (\"off\" or \"jod:T\")");
      p.quality = v.get<std::string>() == "off" ? "" : v.get<std::string>();
    } else if (k == "temporal") {
      if (!v.is_string() || (v.get<std::string>() != "on" && v.get<std::string>() != "off"))
        return bad_input(where + ": temporal: expected \"on\" or \"off\"");
      p.temporal = v.get<std::string>() == "on";
    } else if (k == "gaze_quality") {
      auto q = quality_from_json(v, where);
      if (!q) return q.error();
      p.gaze_quality = std::move(*q);
    } else {
      return bad_input(where + ": unknown key '" + k + "'");
    }
  }
  if (Status s = p.validate(where); !s) return s.error();
  return p;
}

Status Profile::set(const std::string& key, const std::string& value) {
  nlohmann::json j = to_json();
  if ((!j.contains(key) && key != "quality" && key != "temporal") || key == "format") return bad_input("profile " + name + ": unknown key '" + key + "'");
  if (key == "filter") {
    auto parsed = parse_json(value, "profile " + name + ": filter");
    if (!parsed) return parsed.error();
    j[key] = std::move(*parsed);
  } else if (key == "dominant_eye" || key == "display_model" || key == "quality" || key == "temporal" || value == "auto") {
    j[key] = value;
  } else {
    char* end = nullptr;
    errno = 0;
    const double d = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0') return bad_input("profile " + name + ": " + key + ": '" + value + "' is not a number");
    if (errno == ERANGE || !std::isfinite(d))
      return bad_input("profile " + name + ": " + key + ": '" + value + "' is out of range");
    j[key] = d;
  }
  auto p = from_json(j, name, "profile " + name);
  if (!p) return p.error();
  *this = *p;
  return {};
}

}  // namespace foveal

#include "foveal/core/display_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "foveal/core/data_paths.hpp"
#include "foveal/core/json_file.hpp"
#include "foveal/core/json_text.hpp"

namespace foveal {

namespace {
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
/// The narrowest frustum accepted, in tangent units per axis (about 0.6°).
constexpr float kMinTangentSpan = 0.01f;

// A field that is a number of the wrong kind or size. nlohmann's get<float>() and
// get<int>() cast out-of-range values, which is undefined behaviour.
struct FieldError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

float to_float(const nlohmann::json& v) {
  if (!v.is_number()) throw FieldError("expected a number, got " + json_text(v).substr(0, 40));
  const double d = v.get<double>();
  if (!(std::fabs(d) <= std::numeric_limits<float>::max())) throw FieldError(json_text(v) + " is out of range");
  return static_cast<float>(d);
}

int to_int(const nlohmann::json& v) {
  if (!v.is_number_integer()) throw FieldError("expected an integer, got " + json_text(v).substr(0, 40));
  if (v.is_number_unsigned() ? v.get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<int>::max())
                             : (v.get<std::int64_t>() < std::numeric_limits<int>::min() ||
                                v.get<std::int64_t>() > std::numeric_limits<int>::max()))
    throw FieldError(json_text(v) + " is out of range");
  return static_cast<int>(v.get<std::int64_t>());
}
}  // namespace

const char* eye_name(Eye e) { return e == Eye::left ? "left" : "right"; }

glm::vec2 DisplayModel::focal_px(Eye e) const {
  const EyeFrustum& f = eye(e);
  return {static_cast<float>(eye_width) / (f.tan_right - f.tan_left),
          static_cast<float>(eye_height) / (f.tan_top - f.tan_bottom)};
}

glm::vec2 DisplayModel::principal_point(Eye e) const {
  const EyeFrustum& f = eye(e);
  const glm::vec2 fp = focal_px(e);
  return {-f.tan_left * fp.x, f.tan_top * fp.y};
}

glm::vec2 DisplayModel::direction_to_pixel(Eye e, glm::vec3 dir) const {
  if (!(dir.z < 0.0f)) return {kNaN, kNaN};  // also catches NaN
  const EyeFrustum& f = eye(e);
  const float tx = dir.x / -dir.z;
  const float ty = dir.y / -dir.z;
  const float u = (tx - f.tan_left) / (f.tan_right - f.tan_left);
  const float v = (f.tan_top - ty) / (f.tan_top - f.tan_bottom);
  return {u * static_cast<float>(eye_width), v * static_cast<float>(eye_height)};
}

glm::vec3 DisplayModel::pixel_to_direction(Eye e, glm::vec2 px) const {
  const EyeFrustum& f = eye(e);
  const float tx = f.tan_left + (px.x / static_cast<float>(eye_width)) * (f.tan_right - f.tan_left);
  const float ty = f.tan_top - (px.y / static_cast<float>(eye_height)) * (f.tan_top - f.tan_bottom);
  const glm::vec3 d{tx, ty, -1.0f};
  return d / std::sqrt(tx * tx + ty * ty + 1.0f);
}

DisplayModel DisplayModel::vive_pro_eye() {
  DisplayModel m;
  m.name = "htc_vive_pro_eye";
  m.eye_width = 1440;
  m.eye_height = 1600;
  m.ipd_mm = 63.0f;
  m.refresh_hz = 90.0;
  m.edid_vendor = "HVR";
  constexpr float kFocal = 753.6f;
  const EyeFrustum fr{-720.0f / kFocal, 720.0f / kFocal, -800.0f / kFocal, 800.0f / kFocal};
  m.frustum = {fr, fr};
  return m;
}

Status DisplayModel::validate(const std::string& where) const {
  if (eye_width < 1 || eye_height < 1 || eye_width > 16384 || eye_height > 16384)
    return bad_input(where + ": eye_width/eye_height must be in 1..16384");
  if (!(ipd_mm > 0.0f && ipd_mm < 200.0f)) return bad_input(where + ": ipd_mm must be in (0, 200)");
  // 0 stays "any" (docs/display-model.md); a rate between 0 and 1 Hz is no panel's, and
  // foveald's prediction horizon is one refresh (1e-30 Hz made it overflow).
  if (!(refresh_hz == 0.0 || (refresh_hz >= 1.0 && refresh_hz <= 1000.0)))
    return bad_input(where + ": refresh_hz " + std::to_string(refresh_hz) + " must be 0 (any) or in [1, 1000] Hz");
  if (!edid_vendor.empty() &&
      (edid_vendor.size() != 3 || !std::all_of(edid_vendor.begin(), edid_vendor.end(), [](char c) { return c >= 'A' && c <= 'Z'; })))
    return bad_input(where + ": edid_vendor must be three capital letters (a PNP ID such as \"HVR\")");
  for (Eye e : kEyes) {
    const EyeFrustum& f = eye(e);
    const float v[4] = {f.tan_left, f.tan_right, f.tan_bottom, f.tan_top};
    for (float x : v)
      if (!std::isfinite(x) || std::fabs(x) > 100.0f)
        return bad_input(where + ": " + eye_name(e) + " frustum tangents must be finite");
    if (!(f.tan_left < f.tan_right) || !(f.tan_bottom < f.tan_top))
      return bad_input(where + ": " + eye_name(e) + " frustum needs left < right and bottom < top");
    // The focal length in pixels is the eye's size over these spans: ±1e-30 made it 1e33.
    if (!(f.tan_right - f.tan_left >= kMinTangentSpan) || !(f.tan_top - f.tan_bottom >= kMinTangentSpan))
      return bad_input(where + ": " + eye_name(e) + " frustum spans " + std::to_string(f.tan_right - f.tan_left) + " × " +
                       std::to_string(f.tan_top - f.tan_bottom) + " in tangents; right - left and top - bottom must be at least 0.01 (about 0.6°)");
    const LensDistortion& d = distortion[static_cast<std::size_t>(e)];
    const float dv[8] = {d.center.x, d.center.y, d.k1, d.k2, d.k3, d.channel_scale.x, d.channel_scale.y, d.channel_scale.z};
    for (float x : dv)
      if (!std::isfinite(x) || std::fabs(x) > 100.0f)
        return bad_input(where + ": " + eye_name(e) + " distortion values must be finite");
    if (d.center.x < 0 || d.center.x > 1 || d.center.y < 0 || d.center.y > 1)
      return bad_input(where + ": " + eye_name(e) + " distortion center must lie in [0,1]");
    if (!(d.channel_scale.x > 0 && d.channel_scale.y > 0 && d.channel_scale.z > 0))
      return bad_input(where + ": " + eye_name(e) + " distortion channel_scale must be > 0");
  }
  return {};
}

glm::vec2 LensDistortion::source(glm::vec2 p, int c, const EyeFrustum& f) const {
  const glm::vec2 span(f.tan_right - f.tan_left, f.tan_top - f.tan_bottom);
  const glm::vec2 x = (p - center) * span;
  const float r2 = x.x * x.x + x.y * x.y;
  const float s = channel_scale[c] * (1.0f + r2 * (k1 + r2 * (k2 + r2 * k3)));
  return center + x * s / span;
}

Result<DisplayModel> DisplayModel::load(const std::string& path) {
  auto parsed = read_json_file(path, "display model");
  if (!parsed) return parsed.error();
  const nlohmann::json& j = *parsed;
  if (!j.is_object()) return bad_input(path + ": expected a JSON object");
  DisplayModel m;
  std::string k;
  try {
    for (auto it = j.begin(); it != j.end(); ++it) {
      k = it.key();
      if (k == "name") m.name = it->get<std::string>();
      else if (k == "eye_width") m.eye_width = to_int(*it);
      else if (k == "eye_height") m.eye_height = to_int(*it);
      else if (k == "ipd_mm") m.ipd_mm = to_float(*it);
      else if (k == "refresh_hz") m.refresh_hz = it->get<double>();
      else if (k == "edid_vendor") m.edid_vendor = it->get<std::string>();
      else if (k == "format" || k == "source") continue;
      else if (k == "distortion") {
        for (Eye e : kEyes) {
          const auto& d = it->at(eye_name(e));
          LensDistortion& l = m.distortion[static_cast<std::size_t>(e)];
          l.enabled = true;
          l.center = {to_float(d.at("center").at(0)), to_float(d.at("center").at(1))};
          const auto& k3 = d.at("k");
          l.k1 = to_float(k3.at(0)), l.k2 = to_float(k3.at(1)), l.k3 = to_float(k3.at(2));
          if (d.contains("channel_scale"))
            l.channel_scale = {to_float(d["channel_scale"].at(0)), to_float(d["channel_scale"].at(1)),
                               to_float(d["channel_scale"].at(2))};
        }
      }
      else if (k == "left" || k == "right") {
        EyeFrustum& f = m.frustum[k == "left" ? 0 : 1];
        const auto& t = it->at("tangents");
        f = {to_float(t.at("left")), to_float(t.at("right")), to_float(t.at("bottom")),
             to_float(t.at("top"))};
      } else {
        return bad_input(path + ": unknown key '" + k + "'");
      }
    }
  } catch (const nlohmann::json::exception& ex) {
    return bad_input(path + ": " + k + ": " + ex.what());
  } catch (const FieldError& ex) {
    return bad_input(path + ": " + k + ": " + ex.what());
  }
  if (auto f = j.find("format"); f == j.end() || *f != "foveal-display-model v1")  // value() throws on a non-string
    return bad_input(path + ": field 'format' must be \"foveal-display-model v1\"");
  if (Status s = m.validate(path); !s) return s.error();
  return m;
}

std::string DisplayModel::to_json_text(const std::string& source) const {
  nlohmann::ordered_json j;
  j["format"] = "foveal-display-model v1";
  j["name"] = name;
  if (!source.empty()) j["source"] = source;
  j["eye_width"] = eye_width;
  j["eye_height"] = eye_height;
  j["ipd_mm"] = ipd_mm;
  j["refresh_hz"] = refresh_hz;
  if (!edid_vendor.empty()) j["edid_vendor"] = edid_vendor;
  for (Eye e : kEyes) {
    const EyeFrustum& f = eye(e);
    j[eye_name(e)]["tangents"] = {{"left", f.tan_left}, {"right", f.tan_right}, {"bottom", f.tan_bottom}, {"top", f.tan_top}};
  }
  if (distortion[0].enabled || distortion[1].enabled)
    for (Eye e : kEyes) {
      const LensDistortion& d = distortion[static_cast<std::size_t>(e)];
      j["distortion"][eye_name(e)] = {{"center", {d.center.x, d.center.y}},
                                      {"k", {d.k1, d.k2, d.k3}},
                                      {"channel_scale", {d.channel_scale.x, d.channel_scale.y, d.channel_scale.z}}};
    }
  return json_text(j, 2) + "\n";
}

glm::vec2 LensDistortion::panel(glm::vec2 src, int c, const EyeFrustum& f) const {
  const glm::vec2 span(f.tan_right - f.tan_left, f.tan_top - f.tan_bottom);
  const glm::vec2 y = (src - center) * span;
  const float target = std::sqrt(y.x * y.x + y.y * y.y);
  if (target == 0.0f) return center;
  // Solve g(r) = scale·r·(1 + k1 r² + k2 r⁴ + k3 r⁶) = target for r >= 0.
  const float sc = channel_scale[c];
  float r = target / sc;
  for (int i = 0; i < 30; ++i) {
    const float r2 = r * r;
    const float g = sc * r * (1 + r2 * (k1 + r2 * (k2 + r2 * k3))) - target;
    const float dg = sc * (1 + r2 * (3 * k1 + r2 * (5 * k2 + r2 * 7 * k3)));
    if (!(dg > 0)) return {kNaN, kNaN};
    r -= g / dg;
    if (std::fabs(g) < 1e-7f * target) break;
  }
  if (!(r >= 0) || !std::isfinite(r)) return {kNaN, kNaN};
  return center + y * (r / target) / span;
}

std::string display_model_path(const std::string& spec) {
  const bool is_path = spec.find('/') != std::string::npos || (spec.size() >= 5 && spec.compare(spec.size() - 5, 5, ".json") == 0);
  return is_path ? spec : data_path("data/display/" + spec + ".json");
}

}  // namespace foveal

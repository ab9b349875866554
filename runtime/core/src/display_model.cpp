#include "foveal/core/display_model.hpp"

#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "foveal/core/json_file.hpp"

namespace foveal {

namespace {
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
}

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
  constexpr float kFocal = 753.6f;
  const EyeFrustum fr{-720.0f / kFocal, 720.0f / kFocal, -800.0f / kFocal, 800.0f / kFocal};
  m.frustum = {fr, fr};
  return m;
}

Status DisplayModel::validate(const std::string& where) const {
  if (eye_width < 1 || eye_height < 1 || eye_width > 16384 || eye_height > 16384)
    return bad_input(where + ": eye_width/eye_height must be in 1..16384");
  if (!(ipd_mm > 0.0f && ipd_mm < 200.0f)) return bad_input(where + ": ipd_mm must be in (0, 200)");
  for (Eye e : kEyes) {
    const EyeFrustum& f = eye(e);
    const float v[4] = {f.tan_left, f.tan_right, f.tan_bottom, f.tan_top};
    for (float x : v)
      if (!std::isfinite(x) || std::fabs(x) > 100.0f)
        return bad_input(where + ": " + eye_name(e) + " frustum tangents must be finite");
    if (!(f.tan_left < f.tan_right) || !(f.tan_bottom < f.tan_top))
      return bad_input(where + ": " + eye_name(e) + " frustum needs left < right and bottom < top");
  }
  return {};
}

Result<DisplayModel> DisplayModel::load(const std::string& path) {
  auto parsed = read_json_file(path, "display model");
  if (!parsed) return parsed.error();
  const nlohmann::json& j = *parsed;
  DisplayModel m;
  try {
    for (auto it = j.begin(); it != j.end(); ++it) {
      const std::string& k = it.key();
      if (k == "name") m.name = it->get<std::string>();
      else if (k == "eye_width") m.eye_width = it->get<int>();
      else if (k == "eye_height") m.eye_height = it->get<int>();
      else if (k == "ipd_mm") m.ipd_mm = it->get<float>();
      else if (k == "format" || k == "source" || k == "distortion") continue;
      else if (k == "left" || k == "right") {
        EyeFrustum& f = m.frustum[k == "left" ? 0 : 1];
        const auto& t = it->at("tangents");
        f = {t.at("left").get<float>(), t.at("right").get<float>(), t.at("bottom").get<float>(),
             t.at("top").get<float>()};
      } else {
        return bad_input(path + ": unknown key '" + k + "'");
      }
    }
  } catch (const nlohmann::json::exception& ex) {
    return bad_input(path + ": " + ex.what());
  }
  if (j.value("format", std::string()) != "foveal-display-model v1")
    return bad_input(path + ": field 'format' must be \"foveal-display-model v1\"");
  if (Status s = m.validate(path); !s) return s.error();
  return m;
}

}  // namespace foveal

#include "foveal/render/view_file.hpp"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "foveal/core/json_file.hpp"

namespace foveal::render {

namespace {

Result<glm::vec3> vec3_field(const nlohmann::json& j, const char* key, const std::string& where) {
  if (!j.contains(key) || !j[key].is_array() || j[key].size() != 3) return bad_input(where + ": '" + key + "' must be [x, y, z]");
  glm::vec3 v(0.0f);
  for (int i = 0; i < 3; ++i) {
    const auto& x = j[key][static_cast<std::size_t>(i)];
    if (!x.is_number()) return bad_input(where + ": '" + key + "' must hold numbers");
    const double d = x.get<double>();
    if (!std::isfinite(d) || std::fabs(d) > 3.0e38) return bad_input(where + ": '" + key + "' is out of range");
    v[i] = static_cast<float>(d);
  }
  return v;
}

}  // namespace

Result<ViewPose> read_view_file(const std::string& path) {
  auto j = read_json_file(path, "view file");
  if (!j) return j.error();
  if (!j->is_object()) return bad_input(path + ": expected a JSON object");
  auto eye = vec3_field(*j, "eye", path);
  if (!eye) return eye.error();
  auto target = vec3_field(*j, "target", path);
  if (!target) return target.error();
  glm::vec3 up(0, 1, 0);
  if (j->contains("up")) {
    auto u = vec3_field(*j, "up", path);
    if (!u) return u.error();
    up = *u;
  }
  const glm::vec3 forward = *target - *eye;
  const float along = glm::length(forward), across = glm::length(glm::cross(forward, up));
  if (!(along > 0) || !(across > 0) || !std::isfinite(along) || !std::isfinite(across))
    return bad_input(path + ": eye, target and up do not define a view");
  ViewPose v;
  v.head_to_world = glm::inverse(glm::lookAt(*eye, *target, up));
  if (j->contains("units_per_meter")) {
    const auto& u = (*j)["units_per_meter"];
    if (!u.is_number() || !(u.get<double>() > 0) || !(u.get<double>() < 3.0e38))
      return bad_input(path + ": 'units_per_meter' must be a number > 0");
    v.units_per_meter = u.get<float>();
  }
  v.source = "view file " + path;
  return v;
}

}  // namespace foveal::render

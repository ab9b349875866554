#include "foveal/render/scene.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "foveal/core/json_file.hpp"
#include "scene_internal.hpp"

namespace foveal::render {

float Bounds::radius() const { return 0.5f * glm::length(max - min); }

const std::vector<std::string>& pattern_names() {
  static const std::vector<std::string> names = {"checker", "stripes-h", "stripes-v", "noise"};
  return names;
}

namespace {

// Looks from in front (+z, glTF's "front") and a little above, far enough that the
// bounding sphere fits a 90° field of view.
ViewPose framing_view(const Bounds& b) {
  const glm::vec3 target = b.center();
  const float r = std::max(b.radius(), 1e-4f);
  const glm::vec3 eye = target + glm::normalize(glm::vec3(0.0f, 0.35f, 1.0f)) * (r * 1.6f);
  ViewPose v;
  v.head_to_world = glm::inverse(glm::lookAt(eye, target, glm::vec3(0, 1, 0)));
  v.source = "framing";
  return v;
}

Result<glm::vec3> vec3_field(const nlohmann::json& j, const char* key, const std::string& where) {
  if (!j.contains(key) || !j[key].is_array() || j[key].size() != 3) return bad_input(where + ": '" + key + "' must be [x, y, z]");
  glm::vec3 v(0.0f);
  for (int i = 0; i < 3; ++i) {
    if (!j[key][static_cast<std::size_t>(i)].is_number()) return bad_input(where + ": '" + key + "' must hold numbers");
    v[i] = j[key][static_cast<std::size_t>(i)].get<float>();
    if (!std::isfinite(v[i])) return bad_input(where + ": '" + key + "' is not finite");
  }
  return v;
}

// "<scene>.view.json": {"eye": [x,y,z], "target": [x,y,z], "up": [0,1,0], "units_per_meter": 1}
Status apply_view_file(const std::string& path, Scene& s) {
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
  if (glm::length(*target - *eye) <= 0 || glm::length(glm::cross(*target - *eye, up)) <= 0)
    return bad_input(path + ": eye, target and up do not define a view");
  s.view.head_to_world = glm::inverse(glm::lookAt(*eye, *target, up));
  if (j->contains("units_per_meter")) {
    const auto& u = (*j)["units_per_meter"];
    if (!u.is_number() || !(u.get<double>() > 0)) return bad_input(path + ": 'units_per_meter' must be a number > 0");
    s.view.units_per_meter = u.get<float>();
  }
  s.view.source = "view file " + path;
  return {};
}

}  // namespace

Result<Scene> load_scene(const std::string& spec) {
  if (spec.rfind("pattern:", 0) == 0) return detail::make_pattern_scene(spec);
  auto scene = detail::load_gltf_scene(spec);
  if (!scene) return scene;
  const std::filesystem::path view = std::filesystem::path(spec).replace_extension(".view.json");
  if (std::filesystem::exists(view)) {
    if (Status s = apply_view_file(view.string(), *scene); !s) return s.error();
    return scene;
  }
  if (scene->view.source == "framing") scene->view = framing_view(scene->bounds);
  // A small model seen from close by (ToyCar is 5 cm) would get a 63 mm stereo baseline
  // larger than the view itself: scale the viewer so the baseline stays within 1/20 of the
  // viewing distance, as if the object were larger.
  const float distance = glm::length(glm::vec3(scene->view.head_to_world[3]) - scene->bounds.center());
  scene->view.units_per_meter = std::min(1.0f, distance / (20.0f * 0.063f));
  return scene;
}

}  // namespace foveal::render

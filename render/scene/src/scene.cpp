#include "foveal/render/scene.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include <glm/gtc/matrix_transform.hpp>

#include "foveal/core/data_paths.hpp"
#include "foveal/render/view_file.hpp"
#include "scene_internal.hpp"

namespace foveal::render {

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

}  // namespace

std::vector<std::string> bundled_scene_names() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(data_path("data/scenes"), ec))
    if (e.is_directory()) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

Result<std::string> bundled_scene_path(const std::string& name) {
  // The name picks a folder of data/scenes and nothing else: no separators, no dots.
  const bool plain = !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_';
  });
  std::string list;
  for (const std::string& n : bundled_scene_names()) list += (list.empty() ? "" : ", ") + n;
  if (plain) {
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(data_path("data/scenes/" + name), ec))
      if (e.path().extension() == ".gltf" || e.path().extension() == ".glb") return e.path().string();
  }
  return bad_input("bundled:" + name + ": no such bundled scene (bundled: " + (list.empty() ? "none" : list) + ")");
}

Result<Scene> load_scene(const std::string& spec, const SceneOptions& options) {
  if (spec.rfind("pattern:", 0) == 0) {
    if (!options.variant.empty()) return bad_input(spec + ": a pattern has no material variants");
    return detail::make_pattern_scene(spec);
  }
  if (spec.rfind("bundled:", 0) == 0) {
    auto path = bundled_scene_path(spec.substr(std::string("bundled:").size()));
    if (!path) return path.error();
    return load_scene(*path, options);
  }
  auto scene = detail::load_gltf_scene(spec, options.variant);
  if (!scene) return scene;
  const std::filesystem::path view = std::filesystem::path(spec).replace_extension(".view.json");
  if (std::filesystem::exists(view)) {
    auto pose = read_view_file(view.string());
    if (!pose) return pose.error();
    scene->view = std::move(*pose);
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

void fill_view(Scene& scene) {
  glm::mat4& m = scene.view.head_to_world;
  const glm::vec3 eye(m[3]), centre = scene.bounds.center();
  const glm::vec3 dir = glm::normalize(centre - eye);
  m[3] = glm::vec4(centre - dir * (1.05f * std::max(scene.bounds.radius(), 1e-4f)), 1.0f);
  scene.view.source += ", filled";
}

}  // namespace foveal::render

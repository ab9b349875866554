#include "foveal/render/light_rig.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace foveal::render {

namespace {
const glm::vec3 kSunDir = glm::normalize(glm::vec3(0.35f, 1.0f, 0.25f));
}

glm::mat4 sun_clip_matrix(const Bounds& b) {
  const float r = std::max(b.radius(), 1e-4f);
  const glm::vec3 c = b.center();
  const glm::mat4 view = glm::lookAt(c + kSunDir * (2.0f * r), c, glm::vec3(0, 0, 1));
  return glm::ortho(-r, r, -r, r, 0.5f * r, 3.5f * r) * view;
}

LightBlock make_light_rig(const Bounds& b, int point_lights) {
  LightBlock l;
  const int n = std::clamp(point_lights, 0, kMaxPointLights);
  const glm::vec3 lo = b.min + (b.max - b.min) * 0.1f, hi = b.max - (b.max - b.min) * 0.1f;
  const float range = 0.35f * 2.0f * b.radius();
  // Four warm and cool tints, deterministic so images are reproducible.
  const glm::vec3 tints[4] = {{1.0f, 0.78f, 0.55f}, {0.65f, 0.8f, 1.0f}, {1.0f, 0.9f, 0.8f}, {0.9f, 0.7f, 1.0f}};
  for (int i = 0; i < n; ++i) {
    const glm::vec3 cell(static_cast<float>(i % 4), static_cast<float>((i / 4) % 4), static_cast<float>(i / 16));
    const glm::vec3 p = lo + (hi - lo) * ((cell + 0.5f) / 4.0f);
    l.point_pos_range[static_cast<std::size_t>(i)] = glm::vec4(p, range);
    l.point_color[static_cast<std::size_t>(i)] = glm::vec4(tints[i % 4] * 1.2f, 0.0f);
  }
  l.sun_dir = glm::vec4(kSunDir, 0.0f);
  l.sun_color = glm::vec4(glm::vec3(1.0f, 0.95f, 0.85f) * 2.5f, b.radius());
  l.ambient = glm::vec4(glm::vec3(0.15f), 1.0f);
  l.background = glm::vec4(0.02f, 0.025f, 0.035f, 1.0f);
  const glm::mat4 to_texture = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
  l.sun_matrix = to_texture * sun_clip_matrix(b);
  l.counts = glm::ivec4(n, 1, 0, 0);
  return l;
}

LightBlock make_scene_lights(const std::vector<PunctualLight>& lights) {
  LightBlock l;
  const std::size_t n = std::min(lights.size(), static_cast<std::size_t>(kMaxFileLights));
  for (std::size_t i = 0; i < n; ++i) {
    const PunctualLight& p = lights[i];
    const bool directional = p.type == PunctualLight::Type::directional;
    l.light_pos_range[i] = glm::vec4(p.position, directional ? 0.0f : p.range);
    l.light_color[i] = glm::vec4(p.color * p.intensity, directional ? 0.0f : 1.0f);
    // The specification's angular attenuation: scale 1 / max(0.001, cos inner − cos outer),
    // offset −cos outer · scale; a point light gets scale 0, offset 1 (no cone).
    float scale = 0.0f, offset = 1.0f;
    if (p.type == PunctualLight::Type::spot) {
      scale = 1.0f / std::max(0.001f, std::cos(p.inner_cone) - std::cos(p.outer_cone));
      offset = -std::cos(p.outer_cone) * scale;
    }
    l.light_dir[i] = glm::vec4(p.direction, scale);
    l.light_cone[i] = glm::vec4(offset, 0.0f, 0.0f, 0.0f);
  }
  l.ambient = glm::vec4(glm::vec3(0.0f), 1.0f);
  l.background = glm::vec4(0.02f, 0.025f, 0.035f, 1.0f);
  l.counts = glm::ivec4(0, 0, static_cast<int>(n), 0);
  return l;
}

}  // namespace foveal::render

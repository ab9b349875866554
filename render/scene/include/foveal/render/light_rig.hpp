#pragma once
// The lights of a frame: a grid of point lights spread through the scene's bounds and
// one shadowed directional light. Generated from the bounds so every scene gets the
// same lighting load (64 point lights by default); or the glTF file's own lights
// (make_scene_lights). The layout matches the std140 `Lights` block in
// shaders/common/lighting.glsl.
#include <array>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "foveal/render/scene.hpp"

namespace foveal::render {

inline constexpr int kMaxPointLights = 64;
/// KHR_lights_punctual lights a frame takes from the file (gltf_scene.cpp warns past it).
inline constexpr int kMaxFileLights = 64;

struct LightBlock {  // std140
  std::array<glm::vec4, kMaxPointLights> point_pos_range{};
  std::array<glm::vec4, kMaxPointLights> point_color{};
  glm::vec4 sun_dir{0.0f};    ///< towards the light; w unused
  glm::vec4 sun_color{0.0f};  ///< w: scene radius (shadow normal offset scale)
  glm::vec4 ambient{0.0f};    ///< w: exposure
  glm::vec4 background{0.0f};
  glm::mat4 sun_matrix{1.0f};  ///< world -> shadow map texture space [0,1]³
  glm::ivec4 counts{0};        ///< x: point lights, y: 1 when the shadow map is used, z: file lights
  // The file's lights (KHR_lights_punctual), used instead of the rig's (make_scene_lights).
  std::array<glm::vec4, kMaxFileLights> light_pos_range{};  ///< world xyz, range (0: none)
  std::array<glm::vec4, kMaxFileLights> light_color{};      ///< rgb × intensity, w: 0 directional, 1 point or spot
  std::array<glm::vec4, kMaxFileLights> light_dir{};        ///< where it shines (unit), w: cone scale
  std::array<glm::vec4, kMaxFileLights> light_cone{};       ///< x: cone offset (spot: angular = sat(cos·scale + offset)²)
};

/// `point_lights` in [0, 64].
LightBlock make_light_rig(const Bounds& bounds, int point_lights = kMaxPointLights);

/// The file's lights (at most kMaxFileLights are read), no rig lights, no sun, no shadow
/// map, no ambient; exposure 1 (docs/scenes.md, "Lights").
LightBlock make_scene_lights(const std::vector<PunctualLight>& lights);

/// The directional light's view-projection into clip space (for the shadow pass).
glm::mat4 sun_clip_matrix(const Bounds& bounds);

}  // namespace foveal::render

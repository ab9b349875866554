#pragma once
// The lights of a frame: a grid of point lights spread through the scene's bounds and
// one shadowed directional light. Generated from the bounds so every scene gets the
// same lighting load (64 point lights by default); the layout matches the std140
// `Lights` block in shaders/lighting.frag.
#include <array>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "foveal/render/scene.hpp"

namespace foveal::render {

inline constexpr int kMaxPointLights = 64;

struct LightBlock {  // std140
  std::array<glm::vec4, kMaxPointLights> point_pos_range{};
  std::array<glm::vec4, kMaxPointLights> point_color{};
  glm::vec4 sun_dir{0.0f};    ///< towards the light; w unused
  glm::vec4 sun_color{0.0f};  ///< w: scene radius (shadow normal offset scale)
  glm::vec4 ambient{0.0f};    ///< w: exposure
  glm::vec4 background{0.0f};
  glm::mat4 sun_matrix{1.0f};  ///< world -> shadow map texture space [0,1]³
  glm::ivec4 counts{0};        ///< x: point lights, y: 1 when the shadow map is used
};

/// `point_lights` in [0, 64].
LightBlock make_light_rig(const Bounds& bounds, int point_lights = kMaxPointLights);

/// The directional light's view-projection into clip space (for the shadow pass).
glm::mat4 sun_clip_matrix(const Bounds& bounds);

}  // namespace foveal::render

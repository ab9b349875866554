#pragma once
// Per-eye view and projection: the head pose from the scene, each eye half the IPD to
// its side, and the display model's asymmetric frustum (docs/conventions.md).
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "foveal/core/display_model.hpp"
#include "foveal/render/scene.hpp"

namespace foveal::render {

struct EyeView {
  glm::mat4 view{1.0f}, proj{1.0f}, view_proj{1.0f}, inv_view_proj{1.0f};
  glm::vec3 position{0.0f};  ///< world space
};

/// Near and far planes follow the scene's bounds as seen from the head.
EyeView eye_view(const Scene& scene, const DisplayModel& model, Eye eye);

}  // namespace foveal::render

#pragma once
// Per-eye view and projection: the scene's view composed with the head pose, each eye
// half the IPD to its side, and the display model's asymmetric frustum
// (docs/conventions.md, docs/scenes.md "Camera").
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "foveal/core/display_model.hpp"
#include "foveal/core/pose.hpp"
#include "foveal/render/scene.hpp"

namespace foveal::render {

struct EyeView {
  glm::mat4 view{1.0f}, proj{1.0f}, view_proj{1.0f}, inv_view_proj{1.0f};
  glm::vec3 position{0.0f};  ///< world space
};

/// The head in the world: scene.view.head_to_world · head (the head's translation scaled
/// from metres into scene units). `head` must be finite with a unit orientation; the
/// identity gives head_to_world exactly.
glm::mat4 head_to_world(const Scene& scene, const Pose& head);

/// One eye's camera: `ipd_mm / 2` (in metres, scaled into scene units) to its side of the
/// head along the head's x axis. Near and far planes follow the scene's bounds as seen
/// from the eye.
EyeView eye_view(const Scene& scene, const DisplayModel& model, Eye eye, const Pose& head, double ipd_mm);

}  // namespace foveal::render

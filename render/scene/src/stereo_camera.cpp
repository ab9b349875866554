#include "foveal/render/stereo_camera.hpp"

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

namespace foveal::render {

glm::mat4 head_to_world(const Scene& scene, const Pose& head) {
  if (head == Pose{}) return scene.view.head_to_world;
  glm::mat4 pose = glm::mat4_cast(head.orientation);
  pose[3] = glm::vec4(head.position_m * scene.view.units_per_meter, 1.0f);
  return scene.view.head_to_world * pose;
}

EyeView eye_view(const Scene& scene, const DisplayModel& model, Eye eye, const Pose& head, double ipd_mm) {
  // In float, as before the IPD became a parameter: the display model's default gives
  // the same bits as it always did.
  const float half_ipd = 0.5f * static_cast<float>(ipd_mm) / 1000.0f * scene.view.units_per_meter;
  const float side = eye == Eye::left ? -1.0f : 1.0f;
  const glm::mat4 eye_to_world = head_to_world(scene, head) * glm::translate(glm::mat4(1.0f), glm::vec3(side * half_ipd, 0, 0));
  EyeView v;
  v.view = glm::inverse(eye_to_world);
  v.position = glm::vec3(eye_to_world[3]);

  float far_plane = 1.0f;
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 corner((c & 1) ? scene.bounds.max.x : scene.bounds.min.x, (c & 2) ? scene.bounds.max.y : scene.bounds.min.y,
                           (c & 4) ? scene.bounds.max.z : scene.bounds.min.z);
    far_plane = std::max(far_plane, glm::length(corner - v.position));
  }
  far_plane *= 1.05f;
  const float near_plane = far_plane * 1e-3f;
  const EyeFrustum& t = model.eye(eye);
  v.proj = glm::frustum(t.tan_left * near_plane, t.tan_right * near_plane, t.tan_bottom * near_plane, t.tan_top * near_plane,
                        near_plane, far_plane);
  v.view_proj = v.proj * v.view;
  v.inv_view_proj = glm::inverse(v.view_proj);
  return v;
}

}  // namespace foveal::render

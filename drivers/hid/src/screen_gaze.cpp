#include "foveal/drivers/hid/screen_gaze.hpp"

#include <cmath>

#include <glm/geometric.hpp>

namespace foveal::hid {

ScreenPlane ScreenPlane::from(const TrackerConfiguration& config, const TrackerCapabilities& caps) {
  ScreenPlane p;
  p.width_mm = config.screen_width_mm > 0 ? config.screen_width_mm : caps.max_screen_width_mm;
  p.height_mm = config.screen_height_mm > 0 ? config.screen_height_mm : caps.max_screen_height_mm;
  if (caps.optimum_distance_mm > 0) p.viewing_distance_mm = caps.optimum_distance_mm;
  return p;
}

namespace {

/// Screen frame (x right, y down, z towards the user) to head frame (x right, y up,
/// -z forward): only y flips, since the user faces the screen.
glm::dvec3 to_head(const glm::dvec3& v) { return {v.x, -v.y, v.z}; }

void fill_eye(EyeSample& out, const glm::dvec3& eye_screen, const glm::dvec3& gaze_screen, bool origin_known,
              const glm::dvec3& head_centre_screen) {
  const glm::dvec3 ray = to_head(gaze_screen - eye_screen);
  const double len = glm::length(ray);
  if (!(len > 0) || !std::isfinite(len)) return;
  out.direction = glm::vec3(ray / len);
  out.valid |= kValidDirection;
  if (origin_known) {
    out.origin_mm = glm::vec3(to_head(eye_screen - head_centre_screen));
    out.valid |= kValidOrigin;
  }
}

}  // namespace

GazeSample screen_gaze_to_sample(const TrackingData& data, const ScreenPlane& plane) {
  GazeSample s;
  if (!data.gaze_valid) return s;
  const glm::dvec3 gaze{data.gaze_x_mm, data.gaze_y_mm, 0.0};
  // Nominal eyes: centred on the screen (or on the gaze point's origin if the size is
  // unknown), IPD apart, at the viewing distance.
  const glm::dvec3 centre{plane.width_mm / 2, plane.height_mm / 2, plane.viewing_distance_mm};
  const glm::dvec3 half_ipd{plane.ipd_mm / 2, 0.0, 0.0};
  const bool both = data.left_valid && data.right_valid;
  const glm::dvec3 left = data.left_valid ? data.left_eye_mm : centre - half_ipd;
  const glm::dvec3 right = data.right_valid ? data.right_eye_mm : centre + half_ipd;
  const glm::dvec3 head = both ? (left + right) / 2.0 : centre;
  fill_eye(s.eyes[0], left, gaze, both, head);
  fill_eye(s.eyes[1], right, gaze, both, head);
  fill_eye(s.combined, head, gaze, both, head);
  return s;
}

}  // namespace foveal::hid

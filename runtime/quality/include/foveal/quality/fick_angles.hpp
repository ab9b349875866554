#pragma once
// Gaze directions as Fick angles (azimuth first, then elevation), the angles the
// data-quality measures are defined on (docs/quality.md).
#include <glm/vec3.hpp>
#include <glm/ext/vector_double3.hpp>

namespace foveal {

struct FickAngles {
  double azimuth_deg = 0;    ///< positive to the right
  double elevation_deg = 0;  ///< positive up
};

/// From a direction in the eye/head frame (x right, y up, -z forward; any length > 0).
FickAngles fick_from_direction(const glm::dvec3& d);
/// The unit direction in the eye/head frame (x right, y up, -z forward).
glm::dvec3 direction_from_fick(const FickAngles& a);

}  // namespace foveal

#pragma once
// For the quality tests: a direction a known angle away from a target.
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "foveal/quality/fick_angles.hpp"

namespace foveal::test {

/// `target` turned by offset_deg on the sphere towards toward_deg (0 = right, 90 = up).
inline glm::dvec3 turned(const FickAngles& target, double offset_deg, double toward_deg) {
  const glm::dvec3 t = direction_from_fick(target);
  const glm::dvec3 right = glm::normalize(glm::cross(t, glm::dvec3(0, 1, 0)));
  const glm::dvec3 up = glm::cross(right, t);
  const double a = offset_deg * std::numbers::pi / 180, w = toward_deg * std::numbers::pi / 180;
  return std::cos(a) * t + std::sin(a) * (std::cos(w) * right + std::sin(w) * up);
}

}  // namespace foveal::test

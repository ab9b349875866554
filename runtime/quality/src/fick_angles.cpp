#include "foveal/quality/fick_angles.hpp"

#include <cmath>
#include <numbers>

namespace foveal {

namespace {
constexpr double kDegPerRad = 180.0 / std::numbers::pi;
}

FickAngles fick_from_direction(const glm::dvec3& d) {
  // Forward is -z: azimuth about the vertical axis first, then elevation out of the
  // horizontal plane. Both atan2 forms are independent of the vector's length.
  const double forward = -d.z;
  return {std::atan2(d.x, forward) * kDegPerRad, std::atan2(d.y, std::hypot(d.x, forward)) * kDegPerRad};
}

glm::dvec3 direction_from_fick(const FickAngles& a) {
  const double az = a.azimuth_deg / kDegPerRad, el = a.elevation_deg / kDegPerRad;
  return {std::cos(el) * std::sin(az), std::sin(el), -std::cos(el) * std::cos(az)};
}

}  // namespace foveal

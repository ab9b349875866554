#include "foveal/bench/camera_path.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include <glm/gtc/quaternion.hpp>
#include <glm/geometric.hpp>

namespace foveal::bench {

std::string CameraPath::text() const {
  std::ostringstream s;
  s.precision(6);
  switch (kind) {
    case Kind::still: return "static";
    case Kind::recorded: return "recorded";
    case Kind::orbit: s << "orbit"; break;
    case Kind::dolly: s << "dolly"; break;
  }
  if (speed > 0) s << ":" << speed;
  return s.str();
}

Result<CameraPath> parse_camera_path(const std::string& spec, const std::string& option) {
  const std::size_t colon = spec.find(':');
  const std::string name = spec.substr(0, colon);
  CameraPath p;
  if (name == "static") p.kind = CameraPath::Kind::still;
  else if (name == "recorded") p.kind = CameraPath::Kind::recorded;
  else if (name == "orbit") p.kind = CameraPath::Kind::orbit;
  else if (name == "dolly") p.kind = CameraPath::Kind::dolly;
  else return bad_input(option + ": '" + spec + "': expected static, orbit[:DEG_PER_S], dolly[:M_PER_S] or recorded");
  if (colon == std::string::npos) return p;
  if (p.kind == CameraPath::Kind::still || p.kind == CameraPath::Kind::recorded)
    return bad_input(option + ": '" + spec + "': " + name + " takes no speed");
  const std::string value = spec.substr(colon + 1);
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end || !std::isfinite(v) || v <= 0)
    return bad_input(option + ": '" + spec + "': the speed '" + value + "' is not a positive number (" +
                     (p.kind == CameraPath::Kind::orbit ? "degrees" : "metres") + " per second)");
  p.speed = v;
  return p;
}

CameraPath with_default_speed(CameraPath path, double pivot_m) {
  if (path.speed > 0) return path;
  if (path.kind == CameraPath::Kind::orbit) path.speed = kDefaultOrbitDegPerS;
  if (path.kind == CameraPath::Kind::dolly) path.speed = kDefaultDollyPivotsPerS * pivot_m;
  return path;
}

ViewGeometry view_geometry(const glm::mat4& head_to_world, float units_per_meter, const glm::vec3& bounds_center, float bounds_radius) {
  const glm::vec3 eye(head_to_world[3]);
  const glm::vec3 forward = -glm::normalize(glm::vec3(head_to_world[2]));
  return {glm::dot(bounds_center - eye, forward) / units_per_meter, std::max(bounds_radius, 1e-6f) / units_per_meter};
}

double default_pivot_m(const ViewGeometry& g) { return std::clamp(g.ahead_m, 0.5 * g.radius_m, g.radius_m); }

double fill_offset_m(const ViewGeometry& g) { return std::max(0.0, g.ahead_m - 1.05 * g.radius_m); }

double back_and_forth(double s, double lo, double hi) {
  const double span = hi - lo;
  const double u = std::fmod(std::fmod(s - lo, 2 * span) + 2 * span, 2 * span);  // from lo, rising first
  return u <= span ? lo + u : hi - (u - span);
}

Pose camera_pose(const CameraPath& path, double pivot_m, double t_s) {
  Pose p;
  if (t_s == 0) return p;
  switch (path.kind) {
    case CameraPath::Kind::still:
    case CameraPath::Kind::recorded: return p;
    case CameraPath::Kind::orbit: {
      // The head on a circle of radius pivot_m about the pivot at (0, 0, -pivot_m),
      // turned by the same angle so that the pivot stays straight ahead.
      const double deg = back_and_forth(path.speed * t_s, -kOrbitHalfRangeDeg, kOrbitHalfRangeDeg);
      const double a = deg * M_PI / 180.0;
      p.position_m = glm::vec3(static_cast<float>(pivot_m * std::sin(a)), 0.0f, static_cast<float>(pivot_m * (std::cos(a) - 1.0)));
      p.orientation = glm::angleAxis(static_cast<float>(a), glm::vec3(0.0f, 1.0f, 0.0f));
      return p;
    }
    case CameraPath::Kind::dolly: {
      const double d = back_and_forth(path.speed * t_s, 0.0, kDollyReach * pivot_m);
      p.position_m = glm::vec3(0.0f, 0.0f, static_cast<float>(-d));
      return p;
    }
  }
  return p;
}

}  // namespace foveal::bench

#include "foveal/image/foveation_plan.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "foveal/image/method_description.hpp"
#include "foveal/rmfr_mapping.hpp"

namespace foveal::render {

namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

glm::dvec3 view_ray(const EyeFrustum& f, glm::dvec2 p) {
  // The tangents grow upwards: p lies 1 - y of the height above the bottom edge.
  const double tx = f.tan_left + p.x * (f.tan_right - f.tan_left);
  const double ty = f.tan_bottom + (1.0 - p.y) * (f.tan_top - f.tan_bottom);
  return glm::normalize(glm::dvec3(tx, ty, -1.0));
}

const char* method_name(Method m) {
  const MethodDescription* d = describe(m);
  return d ? d->name : "?";
}

Result<Method> parse_method(const std::string& s) {
  for (Method m : all_methods())
    if (s == method_name(m)) return m;
  return bad_input("unknown method '" + s + "' (" + method_names_joined(", ") + ")");
}

const std::vector<Method>& all_methods() {
  static const std::vector<Method> m = [] {
    std::vector<Method> all;
    for (std::size_t row = 0; row < described_methods().size(); ++row) all.push_back(described_method(row));
    return all;
  }();
  return m;
}

const std::vector<std::string>& method_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (Method m : all_methods()) n.emplace_back(method_name(m));
    return n;
  }();
  return names;
}

std::string method_names_joined(const std::string& separator) {
  std::string out;
  for (const std::string& n : method_names()) out += (out.empty() ? "" : separator) + n;
  return out;
}

bool is_method(Method m) { return std::find(all_methods().begin(), all_methods().end(), m) != all_methods().end(); }

std::size_t EyePlan::shaded_samples() const {
  // Layered plans (hyperbolic, linear, inset) shade their layers only.
  if (layers.empty()) return static_cast<std::size_t>(buffer_w) * static_cast<std::size_t>(buffer_h);
  std::size_t n = 0;
  for (const Layer& l : layers) n += static_cast<std::size_t>(l.buffer_w) * static_cast<std::size_t>(l.buffer_h);
  return n;
}

double EyePlan::pixels_per_degree() const {
  return static_cast<double>(screen_w) / (frustum.tan_right - frustum.tan_left) * kPi / 180.0;
}

double eccentricity_deg(const EyeFrustum& f, glm::dvec2 p, glm::dvec2 q) {
  const double c = std::clamp(glm::dot(view_ray(f, p), view_ray(f, q)), -1.0, 1.0);
  return std::acos(c) * 180.0 / kPi;
}

glm::dvec2 optical_centre(const EyeFrustum& f) {
  // The axis (tangent 0) lies `up` of the height above the bottom edge; `up` is a float
  // like the tangents, so 1 - up is exact and flips back to it exactly.
  const float up = -f.tan_bottom / (f.tan_top - f.tan_bottom);
  return {-f.tan_left / (f.tan_right - f.tan_left), 1.0 - up};
}

bool follows_gaze(Method m) {
  const MethodDescription* d = describe(m);
  return d && d->fovea == FoveaSource::gaze;
}

Result<EyePlan> plan_eye(Method m, const EyeFoveation& e, int W, int H, const EyeFrustum& frustum) {
  if (!std::isfinite(e.sigma) || e.sigma < 1.0) return bad_input("sigma must be a number >= 1");
  if (!std::isfinite(e.fx) || !std::isfinite(e.fy) || e.fx <= 0 || e.fy <= 0) return bad_input("fx and fy must be numbers > 0");
  if (!std::isfinite(e.kfr_alpha) || e.kfr_alpha <= 0) return bad_input("the KFR alpha must be a number > 0");
  if (!std::isfinite(e.layer_scale) || e.layer_scale < 0) return bad_input("the layer scale must be a number >= 0");
  if (W < 1 || H < 1) return bad_input("empty viewport");
  if (!is_method(m)) return bad_input("unknown foveation method " + std::to_string(static_cast<int>(m)));
  EyePlan p;
  p.method = m;
  p.screen_w = W, p.screen_h = H;
  p.frustum = frustum;
  p.fovea = {rmfr::sanitize_fovea(e.fovea_x), rmfr::sanitize_fovea(e.fovea_y)};
  p.buffer_w = W, p.buffer_h = H;
  // σ = 1 is full-rate rendering for every method; only RMFR's passes run it (identity).
  if (e.sigma <= 1.0 && m != Method::full) m = p.method = Method::rmfr;
  p.sigma = m == Method::full ? 1.0 : e.sigma;  // the methods read σ from here
  const MethodDescription& d = *describe(m);
  if (d.fovea == FoveaSource::optical_centre) p.fovea = optical_centre(frustum);
  if (Status s = d.plan(p, e); !s) return s.error();
  return p;
}

}  // namespace foveal::render

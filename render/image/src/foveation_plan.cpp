#include "foveal/image/foveation_plan.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "foveal/image/kfr_mapping.hpp"
#include "foveal/image/method_description.hpp"
#include "foveal/rmfr_mapping.hpp"

namespace foveal::render {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

struct LayerSpec {
  double ecc_max_deg, pixel_size;
};

// Hyperbolic fall-off as the RMFR paper ran it (after Guenter et al. 2012): three layers
// split at 10° and 20°, pixel sizes 1, 2 and 12.35.
std::vector<LayerSpec> hyperbolic_layers(double k) { return {{10 * k, 1.0}, {20 * k, 2.0}, {kInf, 12.35}}; }

// Linear fall-off (Weier et al. 2016): full rate to 10°, sampling rate falling linearly
// to p_min = 0.047 at 20°, p_min beyond; the ramp in 2° rings, each at the rate of its
// inner edge (never below what the ramp asks for).
std::vector<LayerSpec> linear_layers(double k) {
  constexpr double p_min = 0.047;
  std::vector<LayerSpec> l = {{12 * k, 1.0}};
  for (double e = 12; e < 20; e += 2) {
    const double rate = 1.0 - (1.0 - p_min) * (e - 10) / 10;
    l.push_back({(e + 2) * k, 1.0 / std::sqrt(rate)});
  }
  l.push_back({kInf, 1.0 / std::sqrt(p_min)});
  return l;
}

glm::dvec3 ray(const EyeFrustum& f, glm::dvec2 p) {
  const double tx = f.tan_left + p.x * (f.tan_right - f.tan_left);
  const double ty = f.tan_bottom + p.y * (f.tan_top - f.tan_bottom);
  return glm::normalize(glm::dvec3(tx, ty, -1.0));
}

// Screen rectangle (pixels, GL frame) holding every pixel within `ecc` degrees of the
// fovea: the bounding box of the cone's rim projected onto the image plane.
void cone_rect(const EyeFrustum& f, glm::dvec2 fovea, double ecc_deg, int W, int H, Layer& out) {
  out.x = 0, out.y = 0, out.w = W, out.h = H;
  if (!std::isfinite(ecc_deg) || ecc_deg >= 89.0) return;
  const glm::dvec3 g = ray(f, fovea);
  const glm::dvec3 a = glm::normalize(glm::cross(g, std::abs(g.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0)));
  const glm::dvec3 b = glm::cross(g, a);
  const double e = ecc_deg * kPi / 180.0;
  double x0 = fovea.x * W, x1 = x0, y0 = fovea.y * H, y1 = y0;
  for (int i = 0; i < 64; ++i) {
    const double phi = 2 * kPi * i / 64;
    const glm::dvec3 d = std::cos(e) * g + std::sin(e) * (std::cos(phi) * a + std::sin(phi) * b);
    if (d.z > -1e-6) {
      // Behind the image plane: the rim runs off to infinity in the direction (d.x, d.y).
      if (d.x > 0) x1 = kInf;
      if (d.x < 0) x0 = -kInf;
      if (d.y > 0) y1 = kInf;
      if (d.y < 0) y0 = -kInf;
      continue;
    }
    const double tx = d.x / -d.z, ty = d.y / -d.z;
    const double px = (tx - f.tan_left) / (f.tan_right - f.tan_left) * W;
    const double py = (ty - f.tan_bottom) / (f.tan_top - f.tan_bottom) * H;
    x0 = std::min(x0, px), x1 = std::max(x1, px), y0 = std::min(y0, py), y1 = std::max(y1, py);
  }
  // One pixel of margin for the rim between the 64 samples.
  auto lo = [](double v, int n) { return static_cast<int>(std::clamp(std::floor(v) - 1, 0.0, double(n))); };
  auto hi = [](double v, int n) { return static_cast<int>(std::clamp(std::ceil(v) + 1, 0.0, double(n))); };
  const int ix0 = lo(x0, W), ix1 = hi(x1, W), iy0 = lo(y0, H), iy1 = hi(y1, H);
  out.x = ix0, out.y = iy0, out.w = std::max(ix1 - ix0, 1), out.h = std::max(iy1 - iy0, 1);
  out.x = std::min(out.x, W - out.w), out.y = std::min(out.y, H - out.h);
}

void layout_layers(EyePlan& p, const std::vector<LayerSpec>& specs) {
  p.layers.clear();
  int atlas_y = 0, width = 1;
  for (const LayerSpec& s : specs) {
    Layer l;
    l.ecc_max_deg = s.ecc_max_deg;
    l.pixel_size = s.pixel_size;
    cone_rect(p.frustum, p.fovea, s.ecc_max_deg, p.screen_w, p.screen_h, l);
    l.buffer_w = std::max(1, static_cast<int>(std::ceil(l.w / s.pixel_size)));
    l.buffer_h = std::max(1, static_cast<int>(std::ceil(l.h / s.pixel_size)));
    l.atlas_y = atlas_y;
    atlas_y += l.buffer_h;
    width = std::max(width, l.buffer_w);
    p.layers.push_back(l);
    if (l.w == p.screen_w && l.h == p.screen_h) break;  // covers everything: outer layers unseen
  }
  p.layers.back().ecc_max_deg = kInf;
  p.buffer_w = width;
  p.buffer_h = atlas_y;
}

std::vector<LayerSpec> specs(Method m, double k) { return m == Method::hyperbolic ? hyperbolic_layers(k) : linear_layers(k); }

}  // namespace

const char* method_name(Method m) {
  switch (m) {
    case Method::full: return "full";
    case Method::rmfr: return "rmfr";
    case Method::kfr: return "kfr";
    case Method::hyperbolic: return "hyperbolic";
    case Method::linear: return "linear";
    case Method::uniform: return "uniform";
    case Method::fixed: return "fixed";
  }
  if (const MethodDescription* d = describe(m)) return d->name;
  return "?";
}

Result<Method> parse_method(const std::string& s) {
  for (Method m : all_methods())
    if (s == method_name(m)) return m;
  return bad_input("unknown method '" + s + "' (" + method_names_joined(", ") + ")");
}

const std::vector<Method>& all_methods() {
  static const std::vector<Method> m = [] {
    std::vector<Method> all = {Method::full,   Method::rmfr,    Method::kfr,  Method::hyperbolic,
                               Method::linear, Method::uniform, Method::fixed};
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
  // Layered plans (hyperbolic, linear, described methods) shade their layers only.
  if (layers.empty()) return static_cast<std::size_t>(buffer_w) * static_cast<std::size_t>(buffer_h);
  std::size_t n = 0;
  for (const Layer& l : layers) n += static_cast<std::size_t>(l.buffer_w) * static_cast<std::size_t>(l.buffer_h);
  return n;
}

double EyePlan::pixels_per_degree() const {
  return static_cast<double>(screen_w) / (frustum.tan_right - frustum.tan_left) * kPi / 180.0;
}

double eccentricity_deg(const EyeFrustum& f, glm::dvec2 p, glm::dvec2 q) {
  const double c = std::clamp(glm::dot(ray(f, p), ray(f, q)), -1.0, 1.0);
  return std::acos(c) * 180.0 / kPi;
}

glm::dvec2 optical_centre(const EyeFrustum& f) {
  return {-f.tan_left / (f.tan_right - f.tan_left), -f.tan_bottom / (f.tan_top - f.tan_bottom)};
}

bool follows_gaze(Method m) {
  if (const MethodDescription* d = describe(m)) return d->follows_gaze;
  return m != Method::full && m != Method::uniform && m != Method::fixed;
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
  p.fovea = {rmfr::sanitize_fovea(e.fovea_x), 1.0 - rmfr::sanitize_fovea(e.fovea_y)};
  p.buffer_w = W, p.buffer_h = H;
  // σ = 1 is full-rate rendering for every method; only RMFR's passes run it (identity).
  if (e.sigma <= 1.0 && m != Method::full) m = p.method = Method::rmfr;
  if (const MethodDescription* d = describe(m)) {
    if (!d->follows_gaze) p.fovea = optical_centre(frustum);
    if (Status s = d->plan(p, e); !s) return s.error();
    return p;
  }
  switch (m) {
    case Method::full: break;
    case Method::fixed:
    case Method::uniform:  // no fovea: pinned too, so that the plan does not depend on the gaze
      p.fovea = optical_centre(frustum);
      [[fallthrough]];
    case Method::rmfr:
      p.buffer_w = rmfr::rmfr_buffer_size(W, e.sigma), p.buffer_h = rmfr::rmfr_buffer_size(H, e.sigma);
      // uniform: RMFR's buffer with the identity map, an even grid that the resolve upsamples.
      p.f = m == Method::uniform ? glm::dvec2(rmfr::kRmfrIdentityF)
                                 : glm::dvec2(rmfr::rmfr_effective_f(e.fx, e.sigma, p.fovea.x),
                                              rmfr::rmfr_effective_f(e.fy, e.sigma, p.fovea.y));
      break;
    case Method::kfr: {
      p.buffer_w = rmfr::rmfr_buffer_size(W, e.sigma), p.buffer_h = rmfr::rmfr_buffer_size(H, e.sigma);
      p.kfr_log_max = image::kfr_log_max(W, H, p.fovea.x * W, p.fovea.y * H);
      p.kfr_alpha = e.kfr_alpha;
      break;
    }
    case Method::hyperbolic:
    case Method::linear: {
      double k = e.layer_scale;
      if (k == 0) {
        // Bisect the eccentricity scale (log scale) until the layers shade W·H/σ² samples.
        const double target = static_cast<double>(W) * H / (e.sigma * e.sigma);
        double lo = std::log(1e-3), hi = std::log(1e3);
        for (int i = 0; i < 40; ++i) {
          const double mid = 0.5 * (lo + hi);
          layout_layers(p, specs(m, std::exp(mid)));
          (static_cast<double>(p.shaded_samples()) > target ? hi : lo) = mid;
        }
        k = std::exp(lo);
      }
      p.layer_scale = k;
      layout_layers(p, specs(m, k));
      break;
    }
  }
  return p;
}

}  // namespace foveal::render

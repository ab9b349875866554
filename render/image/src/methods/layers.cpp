// The layered methods (docs/methods.md): nested screen rectangles around the fovea, each
// shaded at its own rate into one atlas, innermost first; the resolve takes, per pixel,
// the innermost layer serving its eccentricity, blended into the next over the last 15%.
// hyperbolic: three layers as the RMFR paper ran Guenter et al. 2012; linear: Weier et
// al. 2016's ramp in 2° rings. With layer_scale 0 the eccentricity thresholds scale until
// the layers shade W·H/σ² samples, like the other methods at σ.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "foveal/image/method_description.hpp"

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

// Screen rectangle (pixels, origin top-left) holding every pixel within `ecc` degrees of the
// fovea: the bounding box of the cone's rim projected onto the image plane.
void cone_rect(const EyeFrustum& f, glm::dvec2 fovea, double ecc_deg, int W, int H, Layer& out) {
  out.x = 0, out.y = 0, out.w = W, out.h = H;
  if (!std::isfinite(ecc_deg) || ecc_deg >= 89.0) return;
  const glm::dvec3 g = view_ray(f, fovea);
  const glm::dvec3 a = glm::normalize(glm::cross(g, std::abs(g.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0)));
  const glm::dvec3 b = glm::cross(g, a);
  const double e = ecc_deg * kPi / 180.0;
  // y: pixels above the bottom edge, the way the tangents grow; turned into the top row at the end.
  double x0 = fovea.x * W, x1 = x0, y0 = (1.0 - fovea.y) * H, y1 = y0;
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
  out.w = std::max(ix1 - ix0, 1), out.h = std::max(iy1 - iy0, 1);
  const int bottom = std::min(iy0, H - out.h);  // its lowest row, counted from the bottom edge
  out.x = std::min(ix0, W - out.w), out.y = H - out.h - bottom;
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

using LayerSpecs = std::vector<LayerSpec> (*)(double k);

Status plan_layers(EyePlan& p, const EyeFoveation& e, LayerSpecs specs) {
  double k = e.layer_scale;
  if (k == 0) {
    // Bisect the eccentricity scale (log scale) until the layers shade W·H/σ² samples.
    const double target = static_cast<double>(p.screen_w) * p.screen_h / (p.sigma * p.sigma);
    double lo = std::log(1e-3), hi = std::log(1e3);
    for (int i = 0; i < 40; ++i) {
      const double mid = 0.5 * (lo + hi);
      layout_layers(p, specs(std::exp(mid)));
      (static_cast<double>(p.shaded_samples()) > target ? hi : lo) = mid;
    }
    k = std::exp(lo);
  }
  p.layer_scale = k;
  layout_layers(p, specs(k));
  return {};
}

Status plan_hyperbolic(EyePlan& p, const EyeFoveation& e) { return plan_layers(p, e, hyperbolic_layers); }
Status plan_linear(EyePlan& p, const EyeFoveation& e) { return plan_layers(p, e, linear_layers); }

// u_layer: the layer a mapping or lighting pass draws; u_layer_rect/atlas/ecc per layer.
constexpr const char* kKernel = R"glsl(
ivec2 method_source_pixel(ivec2 texel) {
  vec4 rect = u_layer_rect[u_layer], atlas = u_layer_atlas[u_layer];
  vec2 local = vec2(texel) - vec2(0.0, atlas.x) + 0.5;
  vec2 p = rect.xy + min(local * atlas.w, rect.zw - 0.5);
  return clamp_pixel(p);
}

vec2 method_source_point(vec2 t) {
  vec4 rect = u_layer_rect[u_layer], atlas = u_layer_atlas[u_layer];
  return rect.xy + (t - vec2(0.0, atlas.x)) * atlas.w;
}

// Layer i's lit value at screen pixel centre p (bilinear, kept inside the layer).
vec4 sample_layer(sampler2D reduced, int i, vec2 p) {
  vec4 rect = u_layer_rect[i], atlas = u_layer_atlas[i];
  vec2 q = clamp((p - rect.xy) / atlas.w, vec2(0.5), atlas.yz - 0.5);
  return texture(reduced, (q + vec2(0.0, atlas.x)) / u_texture_size);
}

// The innermost layer that serves this eccentricity, blended into the next one over
// the last 15% of its range so the rate change leaves no visible edge.
vec4 method_resolve(sampler2D reduced, vec2 p) {
  vec2 p_norm = p / u_screen_size;
  float e = eccentricity_deg(p_norm);
  for (int i = 0; i < u_layer_count - 1; ++i) {
    float e_max = u_layer_ecc[i];
    if (e < e_max) {
      vec4 c = sample_layer(reduced, i, p);
      float t = smoothstep(0.85 * e_max, e_max, e);
      return t > 0.0 ? mix(c, sample_layer(reduced, i + 1, p), t) : c;
    }
  }
  return sample_layer(reduced, u_layer_count - 1, p);
}
)glsl";

constexpr MethodKernel kLayersKernel{"layers", kKernel, /*rmfr_passes=*/false, /*repeats_v=*/false, /*built_up_front=*/true};

}  // namespace

const MethodDescription& hyperbolic_method() {
  static const MethodDescription d{"hyperbolic", FoveaSource::gaze, plan_hyperbolic, &kLayersKernel};
  return d;
}

const MethodDescription& linear_method() {
  static const MethodDescription d{"linear", FoveaSource::gaze, plan_linear, &kLayersKernel};
  return d;
}

}  // namespace foveal::render

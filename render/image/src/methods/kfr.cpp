// KFR, kernel log-polar foveation (Meng et al. 2018; docs/methods.md): RMFR's buffer size
// rule, columns u from the radius r = exp(L·u^(1/α)) around the fovea, rows the angle.
// The CPU twin of the kernel is foveal/image/kfr_mapping.hpp; tests hold the two together.
#include "foveal/image/kfr_mapping.hpp"
#include "foveal/image/method_description.hpp"
#include "foveal/rmfr_mapping.hpp"

namespace foveal::render {

namespace {

Status plan_kfr(EyePlan& p, const EyeFoveation& e) {
  const int W = p.screen_w, H = p.screen_h;
  p.buffer_w = rmfr::rmfr_buffer_size(W, p.sigma), p.buffer_h = rmfr::rmfr_buffer_size(H, p.sigma);
  // L reaches the farthest corner, measured from the bottom edge as the kernel does
  // (either edge gives the same L but for the last bit of rounding).
  p.kfr_log_max = image::kfr_log_max(W, H, p.fovea.x * W, (1.0 - p.fovea.y) * H);
  p.kfr_alpha = e.kfr_alpha;
  return {};
}

// u_kfr = (L, α). The resolve's angle axis wraps around (repeats_v).
constexpr const char* kKernel = R"glsl(
// The authors' pass 1: r = exp(L·u^(1/α)) (twin of image/kfr_mapping.hpp).
ivec2 method_source_pixel(ivec2 texel) {
  vec2 uv = (vec2(texel) + 0.5) / u_buffer_size;
  float r = exp(u_kfr.x * pow(uv.x, 1.0 / u_kfr.y));
  float theta = 2.0 * PI_F * uv.y;
  return clamp_pixel(u_fovea * u_screen_size + r * vec2(cos(theta), sin(theta)));
}

vec2 method_source_point(vec2 t) {
  vec2 uv = t / u_buffer_size;
  float r = exp(u_kfr.x * pow(max(uv.x, 0.0), 1.0 / u_kfr.y));
  float theta = 2.0 * PI_F * uv.y;
  return u_fovea * u_screen_size + r * vec2(cos(theta), sin(theta));
}

vec4 method_resolve(sampler2D reduced, vec2 p) {
  vec2 d = p - u_fovea * u_screen_size;
  float r = max(length(d), 1.0);
  float u = pow(log(r) / u_kfr.x, u_kfr.y);  // the authors' pass 2: u = (ln r / L)^α
  float v = fract(atan(d.y, d.x) / (2.0 * PI_F));  // the sampler repeats in v: no seam
  return texture(reduced, vec2(u, v) * u_buffer_size / u_texture_size);
}
)glsl";

constexpr MethodKernel kKfrKernel{"kfr", kKernel, /*rmfr_passes=*/false, /*repeats_v=*/true, /*built_up_front=*/true};

}  // namespace

const MethodDescription& kfr_method() {
  static const MethodDescription d{"kfr", FoveaSource::gaze, plan_kfr, &kKfrKernel};
  return d;
}

}  // namespace foveal::render

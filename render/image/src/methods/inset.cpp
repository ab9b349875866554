// The inset: what an OpenXR app renders for quad views (DESIGN §17, docs/methods.md
// "inset"), as a foveation method of foveal's own compositor. Each eye shades
//   - an outer image of the whole eye at density 1/σ per axis: round(W/σ) × round(H/σ),
//   - an inner image at full density over a rectangle centred on the fovea: half-extent
//     EyeFoveation::inset_deg (tan of it, in the frustum's tangents; 0: 35% of the
//     tangent half-extent per axis, Quad-Views-Foveated's default), moved inward where it
//     would cross the view's edges, keeping its size,
// and composes them at full resolution: the outer upsampled bilinearly, the inner over it
// with a smoothstep across a band of inset_band_deg inside the inner edges (edges on the
// view's border do not blend). Shaded samples = outer texels + inner pixels.
// `inset` centres the inner view on the gaze, `inset-fixed` on the optical centre.
#include <algorithm>
#include <cmath>
#include <limits>

#include "foveal/image/method_description.hpp"
#include "foveal/rmfr_mapping.hpp"

namespace foveal::render {

namespace {

constexpr double kDefaultShare = 0.35;  // of the tangent half-extent, per axis
constexpr double kPi = 3.14159265358979323846;

// Pixels of an axis of n pixels spanning tangents `span` that the inner view covers:
// round(share · n) by default, else a half-extent of tan(deg) each side; at least 1.
int inset_pixels(double deg, double span, int n) {
  const double share = deg > 0 ? 2.0 * std::tan(deg * kPi / 180.0) / span : kDefaultShare;
  return std::clamp(static_cast<int>(std::lround(share * n)), 1, n);
}

Status plan_inset(EyePlan& p, const EyeFoveation& e) {
  if (!std::isfinite(e.inset_deg) || e.inset_deg < 0 || e.inset_deg >= 89)
    return bad_input("the inset's half-extent must be a number of degrees in [0, 89) (0: 35% of the view)");
  if (!std::isfinite(e.inset_band_deg) || e.inset_band_deg < 0 || e.inset_band_deg > 45)
    return bad_input("the inset's blend band must be a number of degrees in [0, 45]");
  const int W = p.screen_w, H = p.screen_h;
  const double span_x = p.frustum.tan_right - p.frustum.tan_left, span_y = p.frustum.tan_top - p.frustum.tan_bottom;
  const int iw = inset_pixels(e.inset_deg, span_x, W), ih = inset_pixels(e.inset_deg, span_y, H);

  Layer inner;  // one texel per pixel, centred on the fovea, slid inside the view
  inner.ecc_max_deg = std::numeric_limits<double>::infinity();
  inner.pixel_size = 1;
  inner.w = iw, inner.h = ih;
  inner.x = std::clamp(static_cast<int>(std::lround(p.fovea.x * W - 0.5 * iw)), 0, W - iw);
  // Rows counted from the bottom edge, as the shader's run, so that a tie rounds up (and
  // right along x); stored as the top row.
  const int bottom = std::clamp(static_cast<int>(std::lround((1.0 - p.fovea.y) * H - 0.5 * ih)), 0, H - ih);
  inner.y = H - ih - bottom;
  inner.buffer_w = iw, inner.buffer_h = ih, inner.atlas_y = 0;

  Layer outer;  // the whole eye at 1/σ per axis, above the inner view in the atlas
  outer.ecc_max_deg = std::numeric_limits<double>::infinity();
  outer.pixel_size = p.sigma;
  outer.w = W, outer.h = H;
  outer.buffer_w = rmfr::rmfr_buffer_size(W, p.sigma), outer.buffer_h = rmfr::rmfr_buffer_size(H, p.sigma);
  outer.atlas_y = ih;

  p.layers = {inner, outer};
  p.buffer_w = std::max(inner.buffer_w, outer.buffer_w);
  p.buffer_h = inner.buffer_h + outer.buffer_h;
  p.kernel_params = glm::dvec4(e.inset_band_deg, 0.0, 0.0, 0.0);
  return {};
}

// Layer 0 is the inner view, layer 1 the outer one; u_kernel_params.x the band (degrees).
constexpr const char* kKernel = R"glsl(
// Screen pixels per texel of layer i along x and y (1 for the inner view, W/w and H/h outer).
vec2 inset_step(int i) { return u_layer_rect[i].zw / u_layer_atlas[i].yz; }

vec2 method_source_point(vec2 t) {
  return u_layer_rect[u_layer].xy + (t - vec2(0.0, u_layer_atlas[u_layer].x)) * inset_step(u_layer);
}

ivec2 method_source_pixel(ivec2 texel) { return clamp_pixel(method_source_point(vec2(texel) + 0.5)); }

// Layer i's lit colour at screen point p, bilinear, kept inside the layer's texels.
vec4 inset_sample(sampler2D reduced, int i, vec2 p) {
  vec4 rect = u_layer_rect[i], atlas = u_layer_atlas[i];
  vec2 q = clamp((p - rect.xy) / inset_step(i), vec2(0.5), atlas.yz - 0.5);
  return texture(reduced, (q + vec2(0.0, atlas.x)) / u_texture_size);
}

// Along one axis of n pixels whose ends have tangents `tans`: the inner view's weight at
// p, a smoothstep over the band's degrees in from the edges lo and hi (an edge on the
// view's border does not blend: nothing lies beyond it).
float inset_weight(float p, float lo, float hi, float n, vec2 tans, float band) {
  float a = atan(mix(tans.x, tans.y, p / n));
  float d_lo = lo <= 0.0 ? 1e9 : degrees(a - atan(mix(tans.x, tans.y, lo / n)));
  float d_hi = hi >= n ? 1e9 : degrees(atan(mix(tans.x, tans.y, hi / n)) - a);
  float d = min(d_lo, d_hi);
  return band > 0.0 ? smoothstep(0.0, band, d) : step(0.0, d);
}

vec4 method_resolve(sampler2D reduced, vec2 p) {
  vec4 outer = inset_sample(reduced, 1, p);
  vec4 r = u_layer_rect[0];
  float band = u_kernel_params.x;
  float w = inset_weight(p.x, r.x, r.x + r.z, u_screen_size.x, u_tan.xy, band) *
            inset_weight(p.y, r.y, r.y + r.w, u_screen_size.y, u_tan.zw, band);
  return w > 0.0 ? mix(outer, inset_sample(reduced, 0, p), w) : outer;
}
)glsl";

constexpr MethodKernel kInsetKernel{"inset", kKernel, /*rmfr_passes=*/false, /*repeats_v=*/false, /*built_up_front=*/false};

}  // namespace

const MethodDescription& inset_method() {
  static const MethodDescription d{"inset", FoveaSource::gaze, plan_inset, &kInsetKernel};
  return d;
}

const MethodDescription& inset_fixed_method() {
  static const MethodDescription d{"inset-fixed", FoveaSource::optical_centre, plan_inset, &kInsetKernel};
  return d;
}

}  // namespace foveal::render

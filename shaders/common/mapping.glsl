// Which screen pixel each texel of an eye's reduced buffer stands for, and where each
// screen pixel reads the lit reduced buffer, for every method (docs/methods.md).
// Screen positions are eye-viewport pixels in GL's frame (origin bottom-left). RMFR's
// mapping and the view geometry come from foveal-rmfr (render/foveation/glsl), which also
// runs RMFR's mapping and resolve passes (foveal::rmfr::Foveator).
#include "foveal/rmfr_mapping.glsl"

// One program per mapping (the compositor defines MAPPING): a software rasteriser runs
// every side of a branch, even a uniform one, so the choice is made at compile time.
#define MAPPING_RMFR 0    // also full (f = 1e30: identity)
#define MAPPING_KFR 1     // kernel log-polar
#define MAPPING_LAYERS 2  // hyperbolic / linear fall-off: nested rectangles
#define MAPPING_DESCRIBED 3  // a described method: its kernel is spliced in below
#ifndef MAPPING
#define MAPPING MAPPING_RMFR
#endif
const int MAX_LAYERS = 8;
const float PI_F = 3.14159265359;

uniform vec2 u_buffer_size;   // texels in use
uniform vec2 u_texture_size;  // texels allocated (layers: the atlas may be larger)
uniform vec2 u_screen_size;
uniform vec2 u_fovea;         // normalised
uniform vec2 u_f;             // RMFR
uniform vec2 u_kfr;           // L, alpha
uniform vec4 u_tan;           // frustum tangents: left, right, bottom, top
uniform int u_layer;          // layer drawn by the mapping and lighting passes
uniform int u_layer_count;
uniform vec4 u_layer_rect[MAX_LAYERS];   // screen x, y, w, h (pixels)
uniform vec4 u_layer_atlas[MAX_LAYERS];  // atlas y, buffer w, buffer h, pixel size
uniform float u_layer_ecc[MAX_LAYERS];   // degrees; the last is huge
uniform vec4 u_kernel_params;            // a described method's own numbers

ivec2 clamp_pixel(vec2 p) { return clamp(ivec2(floor(p)), ivec2(0), ivec2(u_screen_size) - 1); }

// A described method's kernel (foveal/image/method_description.hpp): the compositor gives
// the program its GLSL as this file; empty for the built-in mappings.
#include "method/kernel"

// The screen pixel whose G-buffer sample fills `texel`.
ivec2 source_pixel(ivec2 texel) {
#if MAPPING == MAPPING_KFR
  // The authors' pass 1: r = exp(L·u^(1/α)) (twin of image/kfr_mapping.hpp).
  vec2 uv = (vec2(texel) + 0.5) / u_buffer_size;
  float r = exp(u_kfr.x * pow(uv.x, 1.0 / u_kfr.y));
  float theta = 2.0 * PI_F * uv.y;
  return clamp_pixel(u_fovea * u_screen_size + r * vec2(cos(theta), sin(theta)));
#elif MAPPING == MAPPING_LAYERS
  vec4 rect = u_layer_rect[u_layer], atlas = u_layer_atlas[u_layer];
  vec2 local = vec2(texel) - vec2(0.0, atlas.x) + 0.5;
  vec2 p = rect.xy + min(local * atlas.w, rect.zw - 0.5);
  return clamp_pixel(p);
#elif MAPPING == MAPPING_DESCRIBED
  return method_source_pixel(texel);
#else
  return foveal_rmfr_source_pixel(texel, u_buffer_size, u_screen_size, u_fovea, u_f);
#endif
}

float eccentricity_deg(vec2 p_norm) { return foveal_eccentricity_deg(p_norm, u_fovea, u_tan); }

// The screen position (pixels, unclamped) that buffer position t (texels, continuous)
// stands for: source_pixel's mapping before it picks and clamps a pixel.
vec2 source_point(vec2 t) {
#if MAPPING == MAPPING_KFR
  vec2 uv = t / u_buffer_size;
  float r = exp(u_kfr.x * pow(max(uv.x, 0.0), 1.0 / u_kfr.y));
  float theta = 2.0 * PI_F * uv.y;
  return u_fovea * u_screen_size + r * vec2(cos(theta), sin(theta));
#elif MAPPING == MAPPING_LAYERS
  vec4 rect = u_layer_rect[u_layer], atlas = u_layer_atlas[u_layer];
  return rect.xy + (t - vec2(0.0, atlas.x)) * atlas.w;
#elif MAPPING == MAPPING_DESCRIBED
  return method_source_point(t);
#else
  return foveal_rmfr_inverse(t / u_buffer_size, u_fovea, u_f) * u_screen_size;
#endif
}

// A texel's footprint on the screen: the mapping's Jacobian at its centre, as the
// screen-pixel steps of one texel step along x (column 0) and y (column 1).
mat2 texel_footprint(ivec2 texel) {
  vec2 t = vec2(texel) + 0.5;
  return mat2(source_point(t + vec2(0.5, 0.0)) - source_point(t - vec2(0.5, 0.0)),
              source_point(t + vec2(0.0, 0.5)) - source_point(t - vec2(0.0, 0.5)));
}

// A texture read filtered over a footprint of texture-coordinate steps dx, dy: one
// trilinear tap at the GL specification's isotropic level of detail. The pattern variant
// of the material pass reads its tile this way; scene materials take the anisotropic
// filter of common/anisotropic_filter.glsl (docs/rmfr.md, "Texture filtering").
vec4 texture_footprint(sampler2D tex, vec2 uv, vec2 dx, vec2 dy) {
  vec2 size = vec2(textureSize(tex, 0));
  float lod = log2(max(length(dx * size), length(dy * size)));
  return textureLod(tex, uv, isnan(lod) || isinf(lod) ? 0.0 : clamp(lod, -16.0, 16.0));
}

// Layer i's lit value at screen pixel centre p (bilinear, kept inside the layer).
vec4 sample_layer(sampler2D reduced, int i, vec2 p) {
  vec4 rect = u_layer_rect[i], atlas = u_layer_atlas[i];
  vec2 q = clamp((p - rect.xy) / atlas.w, vec2(0.5), atlas.yz - 0.5);
  return texture(reduced, (q + vec2(0.0, atlas.x)) / u_texture_size);
}

// The lit colour of screen pixel centre p, read from the eye's reduced buffer (KFR and
// the layers; RMFR resolves through foveal-rmfr).
#if MAPPING != MAPPING_RMFR
vec4 resolve(sampler2D reduced, vec2 p) {
  vec2 p_norm = p / u_screen_size;
#if MAPPING == MAPPING_KFR
  vec2 d = p - u_fovea * u_screen_size;
  float r = max(length(d), 1.0);
  float u = pow(log(r) / u_kfr.x, u_kfr.y);  // the authors' pass 2: u = (ln r / L)^α
  float v = fract(atan(d.y, d.x) / (2.0 * PI_F));  // the sampler repeats in v: no seam
  return texture(reduced, vec2(u, v) * u_buffer_size / u_texture_size);
#elif MAPPING == MAPPING_LAYERS
  // The innermost layer that serves this eccentricity, blended into the next one over
  // the last 15% of its range so the rate change leaves no visible edge.
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
#elif MAPPING == MAPPING_DESCRIBED
  return method_resolve(reduced, p);
#endif
}
#endif

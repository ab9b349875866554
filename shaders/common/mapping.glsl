// Which screen pixel each texel of an eye's reduced buffer stands for, and where each
// screen pixel reads the lit reduced buffer: the uniforms every method's kernel reads,
// and the kernel itself (docs/methods.md).
// Screen positions are eye-viewport pixels in GL's frame (origin bottom-left). RMFR's
// mapping and the view geometry come from foveal-rmfr (render/foveation/glsl), which also
// runs RMFR's mapping and resolve passes (foveal::rmfr::Foveator).
#include "foveal/rmfr_mapping.glsl"

const int MAX_LAYERS = 8;
const float PI_F = 3.14159265359;

uniform vec2 u_buffer_size;   // texels in use
uniform vec2 u_texture_size;  // texels allocated (layers: the atlas may be larger)
uniform vec2 u_screen_size;
uniform vec2 u_fovea;         // normalised, GL frame (method_binding.cpp flips the plan's top-left)
uniform vec2 u_f;             // RMFR
uniform vec2 u_kfr;           // L, alpha
uniform vec4 u_tan;           // frustum tangents: left, right, bottom, top
uniform int u_layer;          // layer drawn by the mapping and lighting passes
uniform int u_layer_count;
uniform vec4 u_layer_rect[MAX_LAYERS];   // screen x, y, w, h (pixels, GL frame: y the bottom row)
uniform vec4 u_layer_atlas[MAX_LAYERS];  // atlas y, buffer w, buffer h, pixel size
uniform float u_layer_ecc[MAX_LAYERS];   // degrees; the last is huge
uniform vec4 u_kernel_params;            // a method's own numbers (EyePlan::kernel_params)
#include "temporal/jitter.glsl"  // RMFR's grid jitter under temporal accumulation (0 without)

ivec2 clamp_pixel(vec2 p) { return clamp(ivec2(floor(p)), ivec2(0), ivec2(u_screen_size) - 1); }

float eccentricity_deg(vec2 p_norm) { return foveal_eccentricity_deg(p_norm, u_fovea, u_tan); }

// The method's kernel (foveal/image/method_description.hpp, render/image/src/methods/):
// the compositor gives each program its method's GLSL as this file (one program per
// kernel: a software rasteriser runs every side of a branch, even a uniform one, so the
// choice is made when the program is built). It defines
// method_source_pixel, method_source_point and (except RMFR's, whose resolve is
// foveal-rmfr's) method_resolve, which resolve.frag calls.
#include "method/kernel"

// The screen pixel whose G-buffer sample fills `texel`.
ivec2 source_pixel(ivec2 texel) { return method_source_pixel(texel); }

// The screen position (pixels, unclamped) that buffer position t (texels, continuous)
// stands for: source_pixel's mapping before it picks and clamps a pixel.
vec2 source_point(vec2 t) { return method_source_point(t); }

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

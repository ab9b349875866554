// foveal-rmfr for an application's lighting shader (docs/rmfr-library.md). Include it
// (or paste foveal::rmfr::glsl_source()) after #version 450; foveal::rmfr::set_uniforms()
// sets the uniforms below from an eye's Plan. A reduced-buffer texel is gl_FragCoord.xy
// minus the origin of the eye's reduced buffer in the render target.
#include "foveal/rmfr_mapping.glsl"

uniform vec2 foveal_rmfr_buffer_size;  // w, h of the reduced buffer
uniform vec2 foveal_rmfr_screen_size;  // W, H of the eye's full-resolution viewport
uniform vec2 foveal_rmfr_fovea;        // normalised, GL frame (origin bottom-left)
uniform vec2 foveal_rmfr_f;            // effective f per axis (1e30 at σ = 1)
uniform vec4 foveal_rmfr_tan;          // frustum tangents: left, right, bottom, top

// The full-resolution pixel whose G-buffer sample the texel holds (GL frame).
ivec2 foveal_rmfr_screen_pixel(ivec2 texel) {
  return foveal_rmfr_source_pixel(texel, foveal_rmfr_buffer_size, foveal_rmfr_screen_size, foveal_rmfr_fovea,
                                  foveal_rmfr_f);
}

// That pixel's centre, normalised (GL frame): the position to rebuild from depth.
vec2 foveal_rmfr_screen_position(ivec2 texel) {
  return (vec2(foveal_rmfr_screen_pixel(texel)) + 0.5) / foveal_rmfr_screen_size;
}

// That pixel's centre in normalised device coordinates ([-1, 1], for inverse(view_proj)).
vec2 foveal_rmfr_ndc(ivec2 texel) { return foveal_rmfr_screen_position(texel) * 2.0 - 1.0; }

// Degrees between the texel's view ray and the fovea's.
float foveal_rmfr_eccentricity_deg(ivec2 texel) {
  return foveal_eccentricity_deg(foveal_rmfr_screen_position(texel), foveal_rmfr_fovea, foveal_rmfr_tan);
}

// Screen pixels the texel stands for along x and y (1 at σ = 1; above 1 in the
// periphery): for a texture LOD or a filter width chosen from the footprint.
vec2 foveal_rmfr_footprint(ivec2 texel) {
  vec2 u0 = vec2(texel) / foveal_rmfr_buffer_size, u1 = (vec2(texel) + 1.0) / foveal_rmfr_buffer_size;
  return (foveal_rmfr_inverse(u1, foveal_rmfr_fovea, foveal_rmfr_f) - foveal_rmfr_inverse(u0, foveal_rmfr_fovea, foveal_rmfr_f)) *
         foveal_rmfr_screen_size;
}

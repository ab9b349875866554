// Temporal accumulation's per-frame jitter of RMFR's reduced-buffer grid (docs/rmfr.md,
// "Temporal accumulation"): texel t (continuous, centres at i + 0.5) stands for buffer
// position rmfr_jittered(t) instead of t, so the kept samples land on other screen pixels
// each frame. Needs foveal/rmfr_mapping.glsl included before it. u_jitter is 0 without
// accumulation, and then rmfr_jittered returns t exactly (every factor stays finite).
#ifndef TEMPORAL_JITTER_GLSL
#define TEMPORAL_JITTER_GLSL

uniform vec2 u_jitter;  // this frame's offset, texels, in (-0.5, 0.5) per axis

// Screen pixels one buffer texel spans along each axis at buffer position t (texels):
// the derivative of RMFR's inverse map. Written as two ratios so f = 1e30 (σ = 1) gives 1.
vec2 rmfr_pixels_per_texel(vec2 t, vec2 buffer_size, vec2 screen_size, vec2 c, vec2 f) {
  vec2 e = t / buffer_size - c;
  vec2 D = foveal_rmfr_side(c, e);
  vec2 g = f + D - min(abs(e), D);
  return (f / g) * ((f + D) / g) * screen_size / buffer_size;
}

// How much of the jitter texel t takes: none where a texel spans a pixel or less (the
// full-resolution pass holds one sample per pixel, so moving there only swaps pixels and
// blurs the fovea), all of it from two pixels a texel on, linear in between.
vec2 rmfr_jitter_share(vec2 t, vec2 buffer_size, vec2 screen_size, vec2 c, vec2 f) {
  return clamp(rmfr_pixels_per_texel(t, buffer_size, screen_size, c, f) - 1.0, vec2(0.0), vec2(1.0));
}

vec2 rmfr_jittered(vec2 t, vec2 jitter, vec2 buffer_size, vec2 screen_size, vec2 c, vec2 f) {
  return t + jitter * rmfr_jitter_share(t, buffer_size, screen_size, c, f);
}

// The texel position whose jittered position is b: rmfr_jittered's inverse by two
// fixed-point steps (the share changes over tens of texels, so they converge at once).
vec2 rmfr_unjittered(vec2 b, vec2 jitter, vec2 buffer_size, vec2 screen_size, vec2 c, vec2 f) {
  vec2 t = b - jitter * rmfr_jitter_share(b, buffer_size, screen_size, c, f);
  return b - jitter * rmfr_jitter_share(t, buffer_size, screen_size, c, f);
}

#endif

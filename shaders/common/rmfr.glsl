// RMFR's rectangular mapping per axis, in normalised coordinates (docs/rmfr.md).
// The C++ twin is render/image/include/foveal/image/rmfr_mapping.hpp; tests hold the
// two together. c is the fovea, f the mapping parameter (1e30 = no warp). Neither
// formula divides by the distance D from the fovea to the edge, so a fovea on a border
// or corner needs no clamping.

// D on the side of d: c below the fovea, 1 - c above it.
vec2 rmfr_side(vec2 c, vec2 d) { return mix(1.0 - c, c, lessThan(d, vec2(0.0))); }

// Screen -> buffer.
vec2 rmfr_forward(vec2 p, vec2 c, vec2 f) {
  vec2 d = p - c;
  return c + d * (f + rmfr_side(c, d)) / (f + abs(d));
}

// Buffer -> screen.
vec2 rmfr_inverse(vec2 u, vec2 c, vec2 f) {
  vec2 e = u - c;
  vec2 D = rmfr_side(c, e);
  return c + e * f / (f + D - min(abs(e), D));
}

// The screen pixel whose G-buffer sample fills buffer texel `texel`.
ivec2 rmfr_source_pixel(ivec2 texel, vec2 buffer_size, vec2 screen_size, vec2 c, vec2 f) {
  vec2 p = rmfr_inverse((vec2(texel) + 0.5) / buffer_size, c, f);
  return clamp(ivec2(floor(p * screen_size)), ivec2(0), ivec2(screen_size) - 1);
}

// foveal-rmfr: RMFR's rectangular mapping per axis and the eye's view geometry, as pure
// functions (no uniforms, no outputs), for any GLSL 4.50 shader (docs/rmfr-library.md).
// Twin of foveal/rmfr_mapping.hpp; tests hold the two together. Normalised coordinates:
// screen p and buffer u in [0, 1], GL frame (origin bottom-left); c the fovea; f the
// mapping parameter per axis (1e30 = no warp). Neither formula divides by the distance D
// from the fovea to the edge, so a fovea on a border or corner needs no clamping.

// D on the side of d: c below the fovea, 1 - c above it.
vec2 foveal_rmfr_side(vec2 c, vec2 d) { return mix(1.0 - c, c, lessThan(d, vec2(0.0))); }

// Screen -> buffer.
vec2 foveal_rmfr_forward(vec2 p, vec2 c, vec2 f) {
  vec2 d = p - c;
  return c + d * (f + foveal_rmfr_side(c, d)) / (f + abs(d));
}

// Buffer -> screen.
vec2 foveal_rmfr_inverse(vec2 u, vec2 c, vec2 f) {
  vec2 e = u - c;
  vec2 D = foveal_rmfr_side(c, e);
  return c + e * f / (f + D - min(abs(e), D));
}

// The screen pixel whose G-buffer sample fills buffer texel `texel`.
ivec2 foveal_rmfr_source_pixel(ivec2 texel, vec2 buffer_size, vec2 screen_size, vec2 c, vec2 f) {
  vec2 p = foveal_rmfr_inverse((vec2(texel) + 0.5) / buffer_size, c, f);
  return clamp(ivec2(floor(p * screen_size)), ivec2(0), ivec2(screen_size) - 1);
}

// The view ray through normalised screen point p; tan = frustum tangents (left, right,
// bottom, top).
vec3 foveal_view_ray(vec2 p, vec4 tan) {
  return normalize(vec3(mix(tan.x, tan.y, p.x), mix(tan.z, tan.w, p.y), -1.0));
}

// Degrees between the view rays through normalised screen points p and q.
float foveal_eccentricity_deg(vec2 p, vec2 q, vec4 tan) {
  return degrees(acos(clamp(dot(foveal_view_ray(p, tan), foveal_view_ray(q, tan)), -1.0, 1.0)));
}

// Radial lens distortion with per-channel scale (docs/display-model.md): where a colour
// channel with scale `scale` of panel point p (normalised) samples the rendered image.
// center: the lens centre (normalised, same frame as p); k: k1, k2, k3.
vec2 foveal_lens_source(vec2 p, vec2 center, vec3 k, float scale, vec4 tan) {
  vec2 span = vec2(tan.y - tan.x, tan.w - tan.z);
  vec2 x = (p - center) * span;
  float r2 = dot(x, x);
  float radial = 1.0 + r2 * (k.x + r2 * (k.y + r2 * k.z));
  return center + x * (scale * radial) / span;
}

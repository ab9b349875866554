// The `pattern:` scenes' surface: a repeating tile in screen space, rotated about the
// viewport centre, unlit. One implementation for the G-buffer pass (pattern.frag) and
// the visibility pipeline's material pass (material.frag).
layout(binding = 0) uniform sampler2D u_tile;
uniform vec2 u_viewport_size;
uniform float u_angle;    // radians
uniform float u_tile_px;  // screen pixels per repeat

// Tile coordinates per screen pixel (the rotation over the repeat).
mat2 pattern_uv_per_pixel() {
  float c = cos(u_angle), s = sin(u_angle);
  return mat2(c, s, -s, c) / u_tile_px;
}

// Tile coordinates at eye-viewport position p (pixels, GL frame).
vec2 pattern_uv(vec2 p) { return pattern_uv_per_pixel() * (p - 0.5 * u_viewport_size); }

// The unlit G-buffer values of a tile colour.
void pattern_texel(vec3 color, out vec4 albedo, out vec4 normal, out vec4 material, out vec4 emissive) {
  albedo = vec4(color, 1.0);
  normal = vec4(encode_normal(vec3(0.0, 0.0, 1.0)), 0.0, 0.0);
  material = vec4(0.0, 1.0, 1.0, 0.0);
  emissive = vec4(0.0);
}

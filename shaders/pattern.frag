// Geometry pass for `pattern:` scenes: a repeating tile in screen space, rotated about
// the viewport centre, written as an unlit surface.
#include "common/gbuffer_encoding.glsl"

layout(binding = 0) uniform sampler2D u_tile;
uniform vec2 u_viewport_origin, u_viewport_size;
uniform float u_angle;    // radians
uniform float u_tile_px;  // screen pixels per repeat

layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_material;
layout(location = 3) out vec4 o_emissive;

void main() {
  vec2 q = gl_FragCoord.xy - u_viewport_origin - 0.5 * u_viewport_size;
  float c = cos(u_angle), s = sin(u_angle);
  vec2 uv = mat2(c, s, -s, c) * q / u_tile_px;
  o_albedo = vec4(texture(u_tile, uv).rgb, 1.0);
  o_normal = vec4(encode_normal(vec3(0.0, 0.0, 1.0)), 0.0, 0.0);
  o_material = vec4(0.0, 1.0, 1.0, 0.0);
  o_emissive = vec4(0.0);
}

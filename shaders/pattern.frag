// Geometry pass for `pattern:` scenes: the tile of common/pattern.glsl at each pixel,
// written as an unlit surface.
#include "common/gbuffer_encoding.glsl"
#include "common/pattern.glsl"

uniform vec2 u_viewport_origin;

layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_material;
layout(location = 3) out vec4 o_emissive;

void main() {
  vec2 uv = pattern_uv(gl_FragCoord.xy - u_viewport_origin);
  pattern_texel(texture(u_tile, uv).rgb, o_albedo, o_normal, o_material, o_emissive);
}

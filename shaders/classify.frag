// Visibility pipeline, before the material passes: each texel of the eye's buffer gets
// its material as a depth value (material_depth), so that each material's pass, drawn
// at its own depth with the test EQUAL, runs only where that material is. Texels with
// nothing behind them are discarded and keep the cleared depth 1.
#include "common/mapping.glsl"
#include "common/visibility_geometry.glsl"

layout(binding = 5) uniform usampler2D u_ids;

void main() {
  uvec2 id = texelFetch(u_ids, source_pixel(ivec2(gl_FragCoord.xy)), 0).rg;
  if (id.x == 0u) discard;
  gl_FragDepth = material_depth(draw_material(id.x - 1u));
}

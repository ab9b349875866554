// Visibility pipeline's material pass: one quad per tile of the material's list
// (material_tiles.comp), in the eye buffer's texels; the depth range places it at the
// material's depth, where the EQUAL test keeps the shader on the material's texels.
#include "common/material_tiles.glsl"

layout(std430, binding = 4) readonly buffer Lists { uint tiles[]; };
uniform uint u_list_base;     // slot × list capacity
uniform uint u_tiles_across;  // tiles per row of the buffer
uniform vec2 u_surface_size;  // texels of the attachment (the viewport)

void main() {
  uint tile = tiles[u_list_base + uint(gl_InstanceID)];
  const vec2 corners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(0, 1), vec2(0, 1), vec2(1, 0), vec2(1, 1));
  vec2 texel = (vec2(tile % u_tiles_across, tile / u_tiles_across) + corners[gl_VertexID]) * float(MATERIAL_TILE);
  gl_Position = vec4(min(texel / u_surface_size, vec2(1.0)) * 2.0 - 1.0, 0.0, 1.0);
}

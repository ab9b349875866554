// Visibility pipeline, between classification and the material passes: which material
// slots each tile of the eye's buffer holds (from the material depth classify.frag
// wrote), appended to each slot's tile list and counted into its indirect draw, so that
// a material's pass draws only the tiles where it is (docs/rmfr.md, "Pipelines").
#include "common/material_tiles.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 7) uniform sampler2D u_material_depth;  // (material + 1) / 2^20; 1: nothing
layout(std430, binding = 3) buffer Commands { TileDrawCommand commands[]; };
layout(std430, binding = 4) writeonly buffer Lists { uint tiles[]; };
uniform uint u_list_capacity;  // tiles per slot's list: all the buffer's tiles

shared uint s_present[MATERIAL_SLOTS / 32];

void main() {
  const uint lanes = gl_WorkGroupSize.x * gl_WorkGroupSize.y;
  for (uint w = gl_LocalInvocationIndex; w < uint(MATERIAL_SLOTS / 32); w += lanes) s_present[w] = 0u;
  barrier();

  ivec2 size = textureSize(u_material_depth, 0);
  ivec2 origin = ivec2(gl_WorkGroupID.xy) * MATERIAL_TILE;
  uint last = 0xffffffffu;  // a tile is mostly one material: one shared atomic per change
  for (int y = int(gl_LocalInvocationID.y); y < MATERIAL_TILE; y += int(gl_WorkGroupSize.y))
    for (int x = int(gl_LocalInvocationID.x); x < MATERIAL_TILE; x += int(gl_WorkGroupSize.x)) {
      ivec2 t = origin + ivec2(x, y);
      if (t.x >= size.x || t.y >= size.y) continue;
      float d = texelFetch(u_material_depth, t, 0).r;
      if (d >= 1.0) continue;  // nothing behind this texel
      uint slot = material_slot(uint(round(d * 1048576.0)) - 1u);
      if (slot == last) continue;
      last = slot;
      atomicOr(s_present[slot >> 5], 1u << (slot & 31u));
    }
  barrier();

  uint tile = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  for (uint w = gl_LocalInvocationIndex; w < uint(MATERIAL_SLOTS / 32); w += lanes)
    for (uint bits = s_present[w]; bits != 0u; bits &= bits - 1u) {
      uint slot = w * 32u + uint(findLSB(bits));
      tiles[slot * u_list_capacity + atomicAdd(commands[slot].instance_count, 1u)] = tile;
    }
}

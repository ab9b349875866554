// Depth peeling of the forward (alphaMode BLEND) draws for the visibility pipeline's
// transparency at the kept samples (docs/rmfr.md, "Transparency at the kept samples";
// render/pipeline/src/transparent_layers.cpp): layer k keeps, per pixel, the nearest
// blended fragment in front of the opaque depth (the depth attachment starts as a copy
// of it, test LESS) and behind layer k-1's. Ids only, as the visibility pass writes them:
// the composite rebuilds the surface from the triangle.
layout(binding = 6) uniform sampler2D u_previous_depth;  // layer k-1's depth (unread for the first)
uniform bool u_first;
uniform uint u_draw;  // index into Scene::draws

layout(location = 0) out uvec2 o_id;  // draw + 1, triangle

void main() {
  // The same fragment rasterises to the same depth in every peel: <= drops exactly the
  // layers already taken (coplanar blended surfaces: the first drawn only).
  if (!u_first && gl_FragCoord.z <= texelFetch(u_previous_depth, ivec2(gl_FragCoord.xy), 0).r) discard;
  o_id = uvec2(u_draw + 1u, uint(gl_PrimitiveID));
}

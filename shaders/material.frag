// Visibility pipeline's material pass: for each texel of the eye's buffer (RMFR's
// transformed buffer, KFR's log-polar buffer, a layer of the atlas, or W×H for full),
// the screen pixel it stands for (the mapping's inverse), the triangle the visibility
// pass saw there, the surface point rebuilt with perspective-correct barycentrics, and
// the glTF material evaluated at it (common/material.glsl, as the G-buffer pass does),
// with the texture level of detail from the texel's footprint on the screen: a peripheral texel
// filters the texture area it covers. Writes the G-buffer layout the lighting pass reads.
// PATTERN: the variant for `pattern:` scenes (common/pattern.glsl), which have no triangles.
#include "common/mapping.glsl"
#ifdef PATTERN
#include "common/gbuffer_encoding.glsl"
#include "common/pattern.glsl"
#else
#include "common/anisotropic_filter.glsl"
#include "common/material.glsl"
#include "common/visibility_geometry.glsl"
layout(binding = 5) uniform usampler2D u_ids;
layout(binding = 6) uniform sampler2D u_depth;  // the visibility pass's depth
uniform mat4 u_view_proj;
// Each material's draw covers its tiles, where the depth test EQUAL picks its texels: the
// test must run before shading (llvmpipe would also choose that here, as nothing in the
// shader writes depth or memory or discards; this makes it a guarantee).
layout(early_fragment_tests) in;
#endif

#ifdef PATTERN
layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_material;
layout(location = 3) out vec4 o_emissive;
#else
#include "common/gbuffer_outputs.glsl"
#endif
layout(location = 4) out float o_depth;

#ifndef PATTERN
// Texture-coordinate steps of one texel step along buffer x and y, per UV set.
vec2 g_dx[2], g_dy[2];

vec4 sample_slot(sampler2D tex, int slot, vec2 uv) {
  mat2 m = mat2(u_uv_matrix[slot]);
  int set = u_uv_set[slot] == 1 ? 1 : 0;
  return texture_anisotropic(tex, uv, m * g_dx[set], m * g_dy[set]);
}
#endif

void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  ivec2 pixel = source_pixel(texel);
  mat2 footprint = texel_footprint(texel);
#ifdef PATTERN
  o_depth = 0.5;  // what the G-buffer pass's full-screen triangle leaves
  mat2 g = pattern_uv_per_pixel() * footprint;
  vec3 color = texture_footprint(u_tile, pattern_uv(vec2(pixel) + 0.5), g[0], g[1]).rgb;
  pattern_texel(color, o_albedo, o_normal, o_material, o_emissive);
#else
  o_depth = texelFetch(u_depth, pixel, 0).r;
  // A software rasteriser shades 2×2 quads and may take the quad's texture level from
  // any of its lanes, those of other materials' texels and of background included: a
  // lane with nothing behind it takes a neighbour's triangle, so its level is sane.
  uvec2 id = texelFetch(u_ids, pixel, 0).rg;
  for (int k = 1; k < 4 && id.x == 0u; ++k)
    id = texelFetch(u_ids, source_pixel(texel ^ ivec2(k & 1, k >> 1)), 0).rg;
  id = id.x == 0u ? uvec2(1u, 0u) : id;
  DrawRecord d = fetch_draw(id.x - 1u);
  uvec3 tri = fetch_triangle(d, id.y);
  Vertex v0 = fetch_vertex(tri.x), v1 = fetch_vertex(tri.y), v2 = fetch_vertex(tri.z);
  mat4 to_clip = u_view_proj * d.model;
  vec4 c0 = to_clip * vec4(v0.position, 1.0), c1 = to_clip * vec4(v1.position, 1.0), c2 = to_clip * vec4(v2.position, 1.0);
  vec2 ndc = (vec2(pixel) + 0.5) / u_screen_size * 2.0 - 1.0;
  Barycentrics b = barycentrics(c0, c1, c2, ndc);

  // UV steps per screen pixel, then per texel through the footprint.
  vec2 ndc_per_pixel = 2.0 / u_screen_size;
  mat2 uv0_per_pixel = mat2(mix3(b.dx, v0.uv, v1.uv, v2.uv) * ndc_per_pixel.x, mix3(b.dy, v0.uv, v1.uv, v2.uv) * ndc_per_pixel.y);
  mat2 uv1_per_pixel = mat2(mix3(b.dx, v0.uv1, v1.uv1, v2.uv1) * ndc_per_pixel.x, mix3(b.dy, v0.uv1, v1.uv1, v2.uv1) * ndc_per_pixel.y);
  mat2 filtered = filter_footprint(footprint);
  mat2 g0 = uv0_per_pixel * filtered, g1 = uv1_per_pixel * filtered;
  g_dx[0] = g0[0], g_dy[0] = g0[1], g_dx[1] = g1[0], g_dy[1] = g1[1];

  mat3 normal_matrix = mat3(d.normal_matrix[0].xyz, d.normal_matrix[1].xyz, d.normal_matrix[2].xyz);
  SurfacePoint s;
  s.normal = normal_matrix * mix3(b.l, v0.normal, v1.normal, v2.normal);
  vec4 t = mix3(b.l, v0.tangent, v1.tangent, v2.tangent);
  s.tangent = vec4(mat3(d.model) * t.xyz, t.w);
  s.uv0 = mix3(b.l, v0.uv, v1.uv, v2.uv);
  s.uv1 = mix3(b.l, v0.uv1, v1.uv1, v2.uv1);
  s.color = mix3(b.l, v0.color, v1.color, v2.color);
  s.front_facing = front_facing(c0, c1, c2);
  write_gbuffer(evaluate_material(s, material_base(s)));
#endif
}

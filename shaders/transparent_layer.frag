// Transparency at the kept samples (docs/rmfr.md, "Transparency at the kept samples"):
// one peeled layer of the forward draws (transparent_peel.frag), for one material,
// composited over the eye's lit reduced buffer. Each texel takes its screen pixel (the
// mapping's inverse), the layer's triangle there, rebuilds the surface as material.frag
// does (texture reads filtered over the texel's footprint), evaluates the material and
// lights it as blend.frag does, and leaves alpha to the fixed-function "over" blend.
// As in the material pass, a classification first writes each texel's material as its
// depth and each material's draw tests EQUAL before shading: a software rasteriser runs
// a shader's every instruction for a block unless the block's mask is empty before it,
// so a discard in the shader would have cost every material the whole layer.
// CLASSIFY: that classification (as classify.frag, from the layer's ids).
// Transmission reads the eye's opaque reduced buffer resolved to W×H before the layers
// (common/transmission.glsl), as the blend pass reads its copy of the output.
#define DRAW_UINTS_UNIT 13  // lighting.glsl's sheen table holds unit 11
#include "common/mapping.glsl"
#include "common/visibility_geometry.glsl"
layout(binding = 6) uniform usampler2D u_layer_ids;  // the layer: draw + 1, triangle (W×H)

#ifdef CLASSIFY
void main() {
  uvec2 id = texelFetch(u_layer_ids, source_pixel(ivec2(gl_FragCoord.xy)), 0).rg;
  if (id.x == 0u) discard;
  gl_FragDepth = material_depth(draw_material(id.x - 1u));
}
#else
#include "common/anisotropic_filter.glsl"
#include "common/material.glsl"
#include "common/lighting.glsl"

uniform mat4 u_view_proj;
uniform vec3 u_camera_pos;
#ifdef FEATURE_TRANSMISSION
#include "common/transmission.glsl"
#endif
layout(early_fragment_tests) in;  // the EQUAL test picks the material's texels before shading

layout(location = 0) out vec4 o_color;

// Texture-coordinate steps of one texel step along buffer x and y, per UV set.
vec2 g_dx[2], g_dy[2];

vec4 sample_slot(sampler2D tex, int slot, vec2 uv) {
  mat2 m = mat2(u_uv_matrix[slot]);
  int set = u_uv_set[slot] == 1 ? 1 : 0;
  return texture_anisotropic(tex, uv, m * g_dx[set], m * g_dy[set]);
}

void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  ivec2 pixel = source_pixel(texel);
  // A software rasteriser shades 2×2 quads and may take a quad's texture level from any
  // lane: a lane with nothing in the layer takes a neighbour's triangle (as material.frag).
  uvec2 id = texelFetch(u_layer_ids, pixel, 0).rg;
  for (int k = 1; k < 4 && id.x == 0u; ++k)
    id = texelFetch(u_layer_ids, source_pixel(texel ^ ivec2(k & 1, k >> 1)), 0).rg;
  id = id.x == 0u ? uvec2(1u, 0u) : id;

  DrawRecord d = fetch_draw(id.x - 1u);
  uvec3 tri = fetch_triangle(d, id.y);
  Vertex v0 = fetch_vertex(tri.x), v1 = fetch_vertex(tri.y), v2 = fetch_vertex(tri.z);
  mat4 to_clip = u_view_proj * d.model;
  vec4 c0 = to_clip * vec4(v0.position, 1.0), c1 = to_clip * vec4(v1.position, 1.0), c2 = to_clip * vec4(v2.position, 1.0);
  vec2 ndc = (vec2(pixel) + 0.5) / u_screen_size * 2.0 - 1.0;
  Barycentrics b = barycentrics(c0, c1, c2, ndc);

  vec2 ndc_per_pixel = 2.0 / u_screen_size;
  mat2 uv0_per_pixel = mat2(mix3(b.dx, v0.uv, v1.uv, v2.uv) * ndc_per_pixel.x, mix3(b.dy, v0.uv, v1.uv, v2.uv) * ndc_per_pixel.y);
  mat2 uv1_per_pixel = mat2(mix3(b.dx, v0.uv1, v1.uv1, v2.uv1) * ndc_per_pixel.x, mix3(b.dy, v0.uv1, v1.uv1, v2.uv1) * ndc_per_pixel.y);
  mat2 filtered = filter_footprint(texel_footprint(texel));
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
  vec4 base = material_base(s);
  GBufferTexel g = evaluate_material(s, base);
  float alpha = u_blend ? clamp(base.a, 0.0, 1.0) : 1.0;  // an opaque transmissive surface replaces
  if (u_unlit) {
    o_color = vec4(g.albedo.rgb, alpha);
    return;
  }
  vec3 p = (d.model * vec4(mix3(b.l, v0.position, v1.position, v2.position), 1.0)).xyz;
  vec3 n = decode_normal(g.normal.rg);
#ifdef FEATURE_TRANSMISSION
  if (u_transmission.x > 0.0) {
    vec3 model_scale = vec3(length(d.model[0].xyz), length(d.model[1].xyz), length(d.model[2].xyz));
    o_color = vec4(lit_transmissive(pixel, p, n, u_camera_pos, surface_of(g), s, model_scale), alpha);
    return;
  }
#endif
  o_color = vec4(lit_color(pixel, p, n, u_camera_pos, surface_of(g)), alpha);
}
#endif

// The glTF material (metal-roughness, or spec-gloss converted per sample) at one surface
// point: the one implementation behind the G-buffer pass (gbuffer.frag, textures sampled
// with the rasteriser's derivatives) and the visibility pipeline's material pass
// (material.frag, with the footprint of a reduced-buffer texel). The includer defines
//   vec4 sample_slot(sampler2D tex, int slot, vec2 uv)
// after this file: how a material texture is read at that slot's coordinates.
#include "common/gbuffer_encoding.glsl"
#include "common/spec_gloss.glsl"

// Texture slots, in Material::Slot order.
#define SLOT_BASE 0
#define SLOT_METAL_ROUGH 1
#define SLOT_NORMAL 2
#define SLOT_OCCLUSION 3
#define SLOT_EMISSIVE 4

layout(binding = 0) uniform sampler2D u_base_color_tex;
layout(binding = 1) uniform sampler2D u_metal_rough_tex;   // spec-gloss: specular rgb, glossiness a
layout(binding = 2) uniform sampler2D u_normal_tex;
layout(binding = 3) uniform sampler2D u_occlusion_tex;
layout(binding = 4) uniform sampler2D u_emissive_tex;

uniform vec4 u_base_color;
uniform vec3 u_emissive;
uniform float u_metallic, u_roughness, u_normal_scale, u_occlusion_strength, u_alpha_cutoff;
uniform bool u_unlit, u_double_sided;
uniform ivec4 u_has_tex;   // base colour, metal-rough, normal, occlusion
uniform bool u_has_emissive_tex;
uniform mat3 u_uv_matrix[5];  // KHR_texture_transform per slot (identity without)
uniform int u_uv_set[5];      // 0: TEXCOORD_0, 1: TEXCOORD_1
uniform bool u_spec_gloss;
uniform vec3 u_specular;
uniform float u_glossiness;

// The interpolated vertex attributes at the point.
struct SurfacePoint {
  vec3 normal;   // world space, not normalised
  vec4 tangent;  // world xyz, handedness w
  vec2 uv0, uv1;
  vec4 color;
  bool front_facing;
};

// The G-buffer's four colour targets (layout in docs/rmfr.md).
struct GBufferTexel {
  vec4 albedo;    // rgb base colour, a = 1 unlit
  vec4 normal;    // rg octahedral world normal
  vec4 material;  // metallic, roughness, occlusion
  vec4 emissive;  // linear rgb
};

vec4 sample_slot(sampler2D tex, int slot, vec2 uv);

vec2 slot_uv(int slot, SurfacePoint s) { return (u_uv_matrix[slot] * vec3(u_uv_set[slot] == 1 ? s.uv1 : s.uv0, 1.0)).xy; }

// Base colour and alpha (what the alpha mask tests).
vec4 material_base(SurfacePoint s) {
  vec4 base = u_base_color * s.color;
  if (u_has_tex.x != 0) base *= sample_slot(u_base_color_tex, SLOT_BASE, slot_uv(SLOT_BASE, s));
  return base;
}

bool material_masked_out(vec4 base) { return u_alpha_cutoff >= 0.0 && base.a < u_alpha_cutoff; }

GBufferTexel evaluate_material(SurfacePoint s, vec4 base) {
  vec3 n = normalize(s.normal);
  if (u_double_sided && !s.front_facing) n = -n;
  if (u_has_tex.z != 0) {
    vec3 t = normalize(s.tangent.xyz - n * dot(n, s.tangent.xyz));
    vec3 b = cross(n, t) * s.tangent.w;
    vec3 m = sample_slot(u_normal_tex, SLOT_NORMAL, slot_uv(SLOT_NORMAL, s)).xyz * 2.0 - 1.0;
    m.xy *= u_normal_scale;
    n = normalize(mat3(t, b, n) * m);
  }
  float metallic = u_metallic, roughness = u_roughness, occlusion = 1.0;
  if (u_spec_gloss) {
    vec4 sg = vec4(u_specular, u_glossiness);
    if (u_has_tex.y != 0) sg *= sample_slot(u_metal_rough_tex, SLOT_METAL_ROUGH, slot_uv(SLOT_METAL_ROUGH, s));
    MetalRough mr = spec_gloss_to_metal_rough(base.rgb, sg.rgb, sg.a);
    base.rgb = mr.base_color;
    metallic = mr.metallic;
    roughness = mr.roughness;
  } else if (u_has_tex.y != 0) {
    vec4 mr = sample_slot(u_metal_rough_tex, SLOT_METAL_ROUGH, slot_uv(SLOT_METAL_ROUGH, s));
    roughness *= mr.g;
    metallic *= mr.b;
  }
  if (u_has_tex.w != 0)
    occlusion = 1.0 + u_occlusion_strength * (sample_slot(u_occlusion_tex, SLOT_OCCLUSION, slot_uv(SLOT_OCCLUSION, s)).r - 1.0);
  vec3 emissive = u_emissive;
  if (u_has_emissive_tex) emissive *= sample_slot(u_emissive_tex, SLOT_EMISSIVE, slot_uv(SLOT_EMISSIVE, s)).rgb;

  GBufferTexel g;
  g.albedo = vec4(base.rgb, u_unlit ? 1.0 : 0.0);
  g.normal = vec4(encode_normal(n), 0.0, 0.0);
  g.material = vec4(metallic, roughness, occlusion, 0.0);
  g.emissive = vec4(emissive, 0.0);
  return g;
}

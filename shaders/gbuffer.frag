// Geometry pass: glTF metal-roughness material into the G-buffer (layout in docs/rmfr.md).
// Spec-gloss materials are converted to metal-roughness here, per fragment (docs/scenes.md).
#include "common/gbuffer_encoding.glsl"
#include "common/spec_gloss.glsl"

in vec3 v_normal;
in vec4 v_tangent;
in vec2 v_uv;
in vec2 v_uv1;
in vec4 v_color;

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

layout(location = 0) out vec4 o_albedo;    // rgb base colour, a = 1 unlit
layout(location = 1) out vec4 o_normal;    // rg octahedral world normal
layout(location = 2) out vec4 o_material;  // metallic, roughness, occlusion
layout(location = 3) out vec4 o_emissive;  // linear rgb

vec2 slot_uv(int slot) { return (u_uv_matrix[slot] * vec3(u_uv_set[slot] == 1 ? v_uv1 : v_uv, 1.0)).xy; }

void main() {
  vec4 base = u_base_color * v_color;
  if (u_has_tex.x != 0) base *= texture(u_base_color_tex, slot_uv(SLOT_BASE));
  if (u_alpha_cutoff >= 0.0 && base.a < u_alpha_cutoff) discard;

  vec3 n = normalize(v_normal);
  if (u_double_sided && !gl_FrontFacing) n = -n;
  if (u_has_tex.z != 0) {
    vec3 t = normalize(v_tangent.xyz - n * dot(n, v_tangent.xyz));
    vec3 b = cross(n, t) * v_tangent.w;
    vec3 m = texture(u_normal_tex, slot_uv(SLOT_NORMAL)).xyz * 2.0 - 1.0;
    m.xy *= u_normal_scale;
    n = normalize(mat3(t, b, n) * m);
  }
  float metallic = u_metallic, roughness = u_roughness, occlusion = 1.0;
  if (u_spec_gloss) {
    vec4 sg = vec4(u_specular, u_glossiness);
    if (u_has_tex.y != 0) sg *= texture(u_metal_rough_tex, slot_uv(SLOT_METAL_ROUGH));
    MetalRough mr = spec_gloss_to_metal_rough(base.rgb, sg.rgb, sg.a);
    base.rgb = mr.base_color;
    metallic = mr.metallic;
    roughness = mr.roughness;
  } else if (u_has_tex.y != 0) {
    vec4 mr = texture(u_metal_rough_tex, slot_uv(SLOT_METAL_ROUGH));
    roughness *= mr.g;
    metallic *= mr.b;
  }
  if (u_has_tex.w != 0) occlusion = 1.0 + u_occlusion_strength * (texture(u_occlusion_tex, slot_uv(SLOT_OCCLUSION)).r - 1.0);
  vec3 emissive = u_emissive;
  if (u_has_emissive_tex) emissive *= texture(u_emissive_tex, slot_uv(SLOT_EMISSIVE)).rgb;

  o_albedo = vec4(base.rgb, u_unlit ? 1.0 : 0.0);
  o_normal = vec4(encode_normal(n), 0.0, 0.0);
  o_material = vec4(metallic, roughness, occlusion, 0.0);
  o_emissive = vec4(emissive, 0.0);
}

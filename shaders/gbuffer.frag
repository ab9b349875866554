// Geometry pass: glTF metal-roughness material into the G-buffer (layout in docs/rmfr.md).
#include "common/gbuffer_encoding.glsl"

in vec3 v_normal;
in vec4 v_tangent;
in vec2 v_uv;

layout(binding = 0) uniform sampler2D u_base_color_tex;
layout(binding = 1) uniform sampler2D u_metal_rough_tex;
layout(binding = 2) uniform sampler2D u_normal_tex;
layout(binding = 3) uniform sampler2D u_occlusion_tex;
layout(binding = 4) uniform sampler2D u_emissive_tex;

uniform vec4 u_base_color;
uniform vec3 u_emissive;
uniform float u_metallic, u_roughness, u_normal_scale, u_occlusion_strength, u_alpha_cutoff;
uniform bool u_unlit, u_double_sided;
uniform ivec4 u_has_tex;   // base colour, metal-rough, normal, occlusion
uniform bool u_has_emissive_tex;

layout(location = 0) out vec4 o_albedo;    // rgb base colour, a = 1 unlit
layout(location = 1) out vec4 o_normal;    // rg octahedral world normal
layout(location = 2) out vec4 o_material;  // metallic, roughness, occlusion
layout(location = 3) out vec4 o_emissive;  // linear rgb

void main() {
  vec4 base = u_base_color;
  if (u_has_tex.x != 0) base *= texture(u_base_color_tex, v_uv);
  if (u_alpha_cutoff >= 0.0 && base.a < u_alpha_cutoff) discard;

  vec3 n = normalize(v_normal);
  if (u_double_sided && !gl_FrontFacing) n = -n;
  if (u_has_tex.z != 0) {
    vec3 t = normalize(v_tangent.xyz - n * dot(n, v_tangent.xyz));
    vec3 b = cross(n, t) * v_tangent.w;
    vec3 m = texture(u_normal_tex, v_uv).xyz * 2.0 - 1.0;
    m.xy *= u_normal_scale;
    n = normalize(mat3(t, b, n) * m);
  }
  float metallic = u_metallic, roughness = u_roughness, occlusion = 1.0;
  if (u_has_tex.y != 0) {
    vec4 mr = texture(u_metal_rough_tex, v_uv);
    roughness *= mr.g;
    metallic *= mr.b;
  }
  if (u_has_tex.w != 0) occlusion = 1.0 + u_occlusion_strength * (texture(u_occlusion_tex, v_uv).r - 1.0);
  vec3 emissive = u_emissive;
  if (u_has_emissive_tex) emissive *= texture(u_emissive_tex, v_uv).rgb;

  o_albedo = vec4(base.rgb, u_unlit ? 1.0 : 0.0);
  o_normal = vec4(encode_normal(n), 0.0, 0.0);
  o_material = vec4(metallic, roughness, occlusion, 0.0);
  o_emissive = vec4(emissive, 0.0);
}

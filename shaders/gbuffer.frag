// Geometry pass: glTF metal-roughness material into the G-buffer (layout in docs/rmfr.md).
// Spec-gloss materials are converted to metal-roughness here, per fragment (docs/scenes.md).
// The material itself is common/material.glsl (shared with the visibility pipeline).
#include "common/material.glsl"

in vec3 v_normal;
in vec4 v_tangent;
in vec2 v_uv;
in vec2 v_uv1;
in vec4 v_color;

layout(location = 0) out vec4 o_albedo;    // rgb base colour, a = 1 unlit
layout(location = 1) out vec4 o_normal;    // rg octahedral world normal
layout(location = 2) out vec4 o_material;  // metallic, roughness, occlusion
layout(location = 3) out vec4 o_emissive;  // linear rgb

vec4 sample_slot(sampler2D tex, int slot, vec2 uv) { return texture(tex, uv); }

void main() {
  SurfacePoint s = SurfacePoint(v_normal, v_tangent, v_uv, v_uv1, v_color, gl_FrontFacing);
  vec4 base = material_base(s);
  if (material_masked_out(base)) discard;
  GBufferTexel g = evaluate_material(s, base);
  o_albedo = g.albedo;
  o_normal = g.normal;
  o_material = g.material;
  o_emissive = g.emissive;
}

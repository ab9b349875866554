// Geometry pass: glTF metal-roughness material into the G-buffer (layout in docs/rmfr.md).
// Spec-gloss materials are converted to metal-roughness here, per fragment (docs/scenes.md).
// The material itself is common/material.glsl (shared with the visibility pipeline).
#include "common/material.glsl"
#include "common/gbuffer_outputs.glsl"

in vec3 v_normal;
in vec4 v_tangent;
in vec2 v_uv;
in vec2 v_uv1;
in vec4 v_color;

vec4 sample_slot(sampler2D tex, int slot, vec2 uv) { return texture(tex, uv); }

void main() {
  SurfacePoint s = SurfacePoint(v_normal, v_tangent, v_uv, v_uv1, v_color, gl_FrontFacing);
  vec4 base = material_base(s);
  if (material_masked_out(base)) discard;
  write_gbuffer(evaluate_material(s, base));
}

// Visibility pass: per pixel, which draw and which of its triangles is nearest, nothing
// else (the depth buffer keeps the depth). ALPHA_MASK: the variant for alphaMode MASK
// materials, which tests the base colour's alpha as the G-buffer pass does.
#ifdef ALPHA_MASK
#include "common/material.glsl"

in vec3 v_normal;
in vec4 v_tangent;
in vec2 v_uv;
in vec2 v_uv1;
in vec4 v_color;

vec4 sample_slot(sampler2D tex, int slot, vec2 uv) { return texture(tex, uv); }
#endif

uniform uint u_draw;  // index into Scene::draws

layout(location = 0) out uvec2 o_id;  // draw + 1 (0: nothing), triangle

void main() {
#ifdef ALPHA_MASK
  SurfacePoint s = SurfacePoint(v_normal, v_tangent, v_uv, v_uv1, v_color, gl_FrontFacing);
  if (material_masked_out(material_base(s))) discard;
#endif
  o_id = uvec2(u_draw + 1u, uint(gl_PrimitiveID));
}

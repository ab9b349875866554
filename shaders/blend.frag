// Forward pass of alphaMode BLEND and transmissive surfaces (docs/scenes.md,
// "Transparency", "Materials"): after the eye's lit opaque result is complete at output
// resolution, each blended fragment is
// shaded with the opaque path's material (common/material.glsl) and lights
// (common/lighting.glsl) and composited "over" it by the fixed-function blend with
// alpha = base colour factor × texture × vertex colour alpha. The opaque depth is tested
// here, not by a depth attachment: the output holds both eyes, the depth one eye.
#include "common/material.glsl"
#include "common/lighting.glsl"

in vec3 v_normal;
in vec4 v_tangent;
in vec2 v_uv;
in vec2 v_uv1;
in vec4 v_color;

layout(binding = 6) uniform sampler2D u_opaque_depth;  // this eye's full-resolution depth

uniform ivec2 u_origin;       // the eye's pixel (0,0) in the output
uniform vec2 u_eye_size;      // the eye's W×H
uniform mat4 u_inv_view_proj;
uniform vec3 u_camera_pos;
#ifdef FEATURE_TRANSMISSION
uniform mat4 u_view_proj;
uniform vec3 u_model_scale;  // the draw's scale per axis: the volume's thickness into world units
#include "common/transmission.glsl"
#endif

layout(location = 0) out vec4 o_color;

vec4 sample_slot(sampler2D tex, int slot, vec2 uv) { return texture(tex, uv); }

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy) - u_origin;
  // Behind or at the opaque surface (the opaque passes' test is LESS): hidden.
  if (gl_FragCoord.z >= texelFetch(u_opaque_depth, pixel, 0).r) discard;
  SurfacePoint s = SurfacePoint(v_normal, v_tangent, v_uv, v_uv1, v_color, gl_FrontFacing);
  vec4 base = material_base(s);
  GBufferTexel g = evaluate_material(s, base);
  float alpha = u_blend ? clamp(base.a, 0.0, 1.0) : 1.0;  // an opaque transmissive surface replaces
  if (u_unlit) {
    o_color = vec4(g.albedo.rgb, alpha);
    return;
  }
  // The world position as the lighting pass rebuilds it, from the pixel centre and depth.
  vec2 ndc = (vec2(pixel) + 0.5) / u_eye_size * 2.0 - 1.0;
  vec4 w = u_inv_view_proj * vec4(ndc, gl_FragCoord.z * 2.0 - 1.0, 1.0);
  vec3 p = w.xyz / w.w;
  vec3 n = decode_normal(g.normal.rg);
  Surface surface = surface_of(g);
#ifdef FEATURE_TRANSMISSION
  if (u_transmission.x > 0.0) {
    o_color = vec4(lit_transmissive(pixel, p, n, u_camera_pos, surface, s, u_model_scale), alpha);
    return;
  }
#endif
  o_color = vec4(lit_color(pixel, p, n, u_camera_pos, surface), alpha);
}

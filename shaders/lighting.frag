// Lighting: GGX metal-roughness shading with up to 64 point lights and one directional
// light with a PCF shadow map (the rig), or the glTF file's own lights, on the G-buffer (full method, identity mapping) or on an
// eye's reduced G-buffer (any foveation method). Each texel knows its screen pixel
// through the method's mapping, so positions are rebuilt from depth at the right place. Output: tone-mapped linear colour.
#include "common/mapping.glsl"
#include "common/lighting.glsl"

layout(binding = 0) uniform sampler2D g_albedo;
layout(binding = 1) uniform sampler2D g_normal;
layout(binding = 2) uniform sampler2D g_material;
layout(binding = 3) uniform sampler2D g_emissive;
layout(binding = 4) uniform sampler2D g_depth;
#ifdef FEATURE_CLEARCOAT
layout(binding = CLEARCOAT_UNIT) uniform sampler2D g_clearcoat;
#endif
#ifdef FEATURE_SHEEN
layout(binding = SHEEN_UNIT) uniform sampler2D g_sheen;
#endif
#ifdef FEATURE_SPECULAR
layout(binding = SPECULAR_UNIT) uniform sampler2D g_specular;
#endif
#ifdef FEATURE_ANISOTROPY
layout(binding = ANISOTROPY_UNIT) uniform sampler2D g_anisotropy;
#endif
#ifdef FEATURE_IRIDESCENCE
layout(binding = IRIDESCENCE_UNIT) uniform sampler2D g_iridescence;
#endif

uniform ivec2 u_origin;  // where this eye's texel (0,0) lies in the render target
uniform mat4 u_inv_view_proj;
uniform vec3 u_camera_pos;

layout(location = 0) out vec4 o_color;

void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy) - u_origin;
  ivec2 pixel = source_pixel(texel);
  vec4 albedo = texelFetch(g_albedo, texel, 0);
  float depth = texelFetch(g_depth, texel, 0).r;
  if (albedo.a > 0.5) {  // unlit
    o_color = vec4(albedo.rgb, 1.0);
    return;
  }
  if (depth >= 1.0) {
    o_color = vec4(u_background.rgb, 1.0);
    return;
  }
  vec2 ndc = (vec2(pixel) + 0.5) / u_screen_size * 2.0 - 1.0;
  vec4 w = u_inv_view_proj * vec4(ndc, depth * 2.0 - 1.0, 1.0);
  vec3 p = w.xyz / w.w;
  GBufferTexel g;
  g.albedo = albedo;
  g.normal = texelFetch(g_normal, texel, 0);
  g.material = texelFetch(g_material, texel, 0);
  g.emissive = texelFetch(g_emissive, texel, 0);
#ifdef FEATURE_CLEARCOAT
  g.clearcoat = texelFetch(g_clearcoat, texel, 0);
#endif
#ifdef FEATURE_SHEEN
  g.sheen = texelFetch(g_sheen, texel, 0);
#endif
#ifdef FEATURE_SPECULAR
  g.specular = texelFetch(g_specular, texel, 0);
#endif
#ifdef FEATURE_ANISOTROPY
  g.anisotropy = texelFetch(g_anisotropy, texel, 0);
#endif
#ifdef FEATURE_IRIDESCENCE
  g.iridescence = texelFetch(g_iridescence, texel, 0);
#endif
  o_color = vec4(lit_color(pixel, p, decode_normal(g.normal.rg), u_camera_pos, surface_of(g)), 1.0);
}

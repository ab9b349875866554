// Mapping pass: fills an eye's reduced G-buffer (RMFR's transformed buffer, KFR's
// log-polar buffer, or one layer of the layered methods) with the full-resolution
// G-buffer sample each texel stands for. G-buffer data is fetched, never interpolated:
// a blend of two surfaces' normals or depths is not a surface.
#include "common/mapping.glsl"

layout(binding = 0) uniform sampler2D g_albedo;
layout(binding = 1) uniform sampler2D g_normal;
layout(binding = 2) uniform sampler2D g_material;
layout(binding = 3) uniform sampler2D g_emissive;
layout(binding = 4) uniform sampler2D g_depth;

layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_material;
layout(location = 3) out vec4 o_emissive;
layout(location = 4) out float o_depth;
// The scene's feature targets (common/gbuffer_outputs.glsl's locations, units 8 on).
#ifdef FEATURE_CLEARCOAT
layout(binding = CLEARCOAT_UNIT) uniform sampler2D g_clearcoat;
layout(location = CLEARCOAT_LOCATION) out vec4 o_clearcoat;
#endif
#ifdef FEATURE_SHEEN
layout(binding = SHEEN_UNIT) uniform sampler2D g_sheen;
layout(location = SHEEN_LOCATION) out vec4 o_sheen;
#endif
#ifdef FEATURE_SPECULAR
layout(binding = SPECULAR_UNIT) uniform sampler2D g_specular;
layout(location = SPECULAR_LOCATION) out vec4 o_specular;
#endif
#ifdef FEATURE_ANISOTROPY
layout(binding = ANISOTROPY_UNIT) uniform sampler2D g_anisotropy;
layout(location = ANISOTROPY_LOCATION) out vec4 o_anisotropy;
#endif
#ifdef FEATURE_IRIDESCENCE
layout(binding = IRIDESCENCE_UNIT) uniform sampler2D g_iridescence;
layout(location = IRIDESCENCE_LOCATION) out vec4 o_iridescence;
#endif

void main() {
  ivec2 src = source_pixel(ivec2(gl_FragCoord.xy));
  o_albedo = texelFetch(g_albedo, src, 0);
  o_normal = texelFetch(g_normal, src, 0);
  o_material = texelFetch(g_material, src, 0);
  o_emissive = texelFetch(g_emissive, src, 0);
  o_depth = texelFetch(g_depth, src, 0).r;
#ifdef FEATURE_CLEARCOAT
  o_clearcoat = texelFetch(g_clearcoat, src, 0);
#endif
#ifdef FEATURE_SHEEN
  o_sheen = texelFetch(g_sheen, src, 0);
#endif
#ifdef FEATURE_SPECULAR
  o_specular = texelFetch(g_specular, src, 0);
#endif
#ifdef FEATURE_ANISOTROPY
  o_anisotropy = texelFetch(g_anisotropy, src, 0);
#endif
#ifdef FEATURE_IRIDESCENCE
  o_iridescence = texelFetch(g_iridescence, src, 0);
#endif
}

#ifndef GBUFFER_OUTPUTS_GLSL
#define GBUFFER_OUTPUTS_GLSL
// The G-buffer's colour outputs, for the passes that write it (gbuffer.frag and the
// visibility pipeline's material.frag): the four core targets at locations 0-3 and the
// scene's feature targets at the locations the compositor defines (render_targets.hpp,
// SurfaceLayout; location 4 is the reduced buffers' depth).
layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_material;
layout(location = 3) out vec4 o_emissive;
#ifdef FEATURE_CLEARCOAT
layout(location = CLEARCOAT_LOCATION) out vec4 o_clearcoat;
#endif
#ifdef FEATURE_SHEEN
layout(location = SHEEN_LOCATION) out vec4 o_sheen;
#endif
#ifdef FEATURE_SPECULAR
layout(location = SPECULAR_LOCATION) out vec4 o_specular;
#endif
#ifdef FEATURE_ANISOTROPY
layout(location = ANISOTROPY_LOCATION) out vec4 o_anisotropy;
#endif
#ifdef FEATURE_IRIDESCENCE
layout(location = IRIDESCENCE_LOCATION) out vec4 o_iridescence;
#endif

void write_gbuffer(GBufferTexel g) {
  o_albedo = g.albedo;
  o_normal = g.normal;
  o_material = g.material;
  o_emissive = g.emissive;
#ifdef FEATURE_CLEARCOAT
  o_clearcoat = g.clearcoat;
#endif
#ifdef FEATURE_SHEEN
  o_sheen = g.sheen;
#endif
#ifdef FEATURE_SPECULAR
  o_specular = g.specular;
#endif
#ifdef FEATURE_ANISOTROPY
  o_anisotropy = g.anisotropy;
#endif
#ifdef FEATURE_IRIDESCENCE
  o_iridescence = g.iridescence;
#endif
}
#endif

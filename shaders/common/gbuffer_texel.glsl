#ifndef GBUFFER_TEXEL_GLSL
#define GBUFFER_TEXEL_GLSL
// One G-buffer texel as the material writes it, and the surface the lighting reads from
// it: the one encoding for the deferred passes and the forward blend pass. Features the
// scene does not use are not compiled in (FEATURE_* from the compositor, docs/scenes.md).
#include "common/gbuffer_encoding.glsl"

// The G-buffer's colour targets (layout in docs/rmfr.md): four always, one per feature.
struct GBufferTexel {
  vec4 albedo;    // rgb base colour, a = 1 unlit
  vec4 normal;    // rg octahedral world normal
  vec4 material;  // metallic, roughness, occlusion
  vec4 emissive;  // linear rgb
#ifdef FEATURE_CLEARCOAT
  vec4 clearcoat;  // factor, roughness, ba octahedral coat normal
#endif
#ifdef FEATURE_SHEEN
  vec4 sheen;      // linear colour, roughness
#endif
#ifdef FEATURE_SPECULAR
  vec4 specular;   // sqrt of the dielectric F0 (rgb), F90
#endif
#ifdef FEATURE_ANISOTROPY
  vec4 anisotropy;  // strength, unused, ba octahedral world direction
#endif
#ifdef FEATURE_IRIDESCENCE
  vec4 iridescence;  // factor, film thickness / 2000 nm, (film ior - 1) / 4
#endif
};

// What the BRDF needs at a point (common/lighting.glsl).
struct Surface {
  vec3 albedo;
  float metallic, roughness, occlusion;
  vec3 emissive;
  vec3 f0;    // dielectric F0: 0.04 (ior 1.5) unless KHR_materials_specular / _ior say
  float f90;  // dielectric F90: 1 unless KHR_materials_specular says
#ifdef FEATURE_CLEARCOAT
  float clearcoat, clearcoat_roughness;
  vec3 clearcoat_normal;
#endif
#ifdef FEATURE_SHEEN
  vec3 sheen_color;
  float sheen_roughness;
#endif
#ifdef FEATURE_TRANSMISSION
  float transmission;  // set by the forward pass; the G-buffer never holds a transmissive surface
#endif
#ifdef FEATURE_ANISOTROPY
  float anisotropy;
  vec3 anisotropy_direction;  // world space, not yet orthogonal to the shading normal
#endif
#ifdef FEATURE_IRIDESCENCE
  float iridescence, film_thickness_nm, film_ior;
  vec3 film_fresnel;  // at n·v, set by lit_color for every light
#endif
};

Surface surface_of(GBufferTexel g) {
  Surface s;
  s.albedo = g.albedo.rgb;
  s.metallic = g.material.r;
  s.roughness = g.material.g;
  s.occlusion = g.material.b;
  s.emissive = g.emissive.rgb;
  s.f0 = vec3(0.04);
  s.f90 = 1.0;
#ifdef FEATURE_TRANSMISSION
  s.transmission = 0.0;
#endif
#ifdef FEATURE_SPECULAR
  s.f0 = g.specular.rgb * g.specular.rgb;
  s.f90 = g.specular.a;
#endif
#ifdef FEATURE_CLEARCOAT
  s.clearcoat = g.clearcoat.r;
  s.clearcoat_roughness = g.clearcoat.g;
  s.clearcoat_normal = decode_normal(g.clearcoat.ba);
#endif
#ifdef FEATURE_SHEEN
  s.sheen_color = g.sheen.rgb;
  s.sheen_roughness = g.sheen.a;
#endif
#ifdef FEATURE_ANISOTROPY
  s.anisotropy = g.anisotropy.r;
  s.anisotropy_direction = decode_normal(g.anisotropy.ba);
#endif
#ifdef FEATURE_IRIDESCENCE
  s.iridescence = g.iridescence.r;
  s.film_thickness_nm = g.iridescence.g * 2000.0;
  s.film_ior = 1.0 + 4.0 * g.iridescence.b;
  s.film_fresnel = vec3(0.0);
#endif
  return s;
}
#endif

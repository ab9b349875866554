// The glTF material (metal-roughness, or spec-gloss converted per sample) at one surface
// point: the one implementation behind the G-buffer pass (gbuffer.frag, textures sampled
// with the rasteriser's derivatives) and the visibility pipeline's material pass
// (material.frag, with the footprint of a reduced-buffer texel). The includer defines
//   vec4 sample_slot(sampler2D tex, int slot, vec2 uv)
// after this file: how a material texture is read at that slot's coordinates.
#include "common/gbuffer_texel.glsl"
#include "common/spec_gloss.glsl"

// Texture slots, in Material::Slot order.
#define SLOT_BASE 0
#define SLOT_METAL_ROUGH 1
#define SLOT_NORMAL 2
#define SLOT_OCCLUSION 3
#define SLOT_EMISSIVE 4
#define SLOT_CLEARCOAT 5
#define SLOT_CLEARCOAT_ROUGHNESS 6
#define SLOT_CLEARCOAT_NORMAL 7
#define SLOT_SHEEN_COLOR 8
#define SLOT_SHEEN_ROUGHNESS 9
#define SLOT_SPECULAR 10
#define SLOT_SPECULAR_COLOR 11
#define SLOT_TRANSMISSION 12
#define SLOT_THICKNESS 13
#define SLOT_ANISOTROPY 14
#define SLOT_IRIDESCENCE 15
#define SLOT_IRIDESCENCE_THICKNESS 16
#define SLOT_COUNT 17

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
uniform mat3 u_uv_matrix[SLOT_COUNT];  // KHR_texture_transform per slot (identity without)
uniform int u_uv_set[SLOT_COUNT];      // 0: TEXCOORD_0, 1: TEXCOORD_1
uniform bool u_spec_gloss;
uniform vec3 u_specular;
uniform float u_glossiness;

// The material extensions (docs/scenes.md, "Materials"): compiled in only for a scene
// whose materials use them. Their textures sit on units 16 + (slot - 5); bit (slot - 5)
// of u_ext_tex says the material has one.
uniform int u_ext_tex;
#ifdef FEATURE_CLEARCOAT
layout(binding = 16) uniform sampler2D u_clearcoat_tex;            // r
layout(binding = 17) uniform sampler2D u_clearcoat_roughness_tex;  // g
layout(binding = 18) uniform sampler2D u_clearcoat_normal_tex;
uniform vec3 u_clearcoat;  // factor, roughness, normal scale
#endif
#ifdef FEATURE_SHEEN
layout(binding = 19) uniform sampler2D u_sheen_color_tex;      // rgb, sRGB
layout(binding = 20) uniform sampler2D u_sheen_roughness_tex;  // a
uniform vec4 u_sheen;  // linear colour, roughness
#endif
#ifdef FEATURE_SPECULAR
layout(binding = 21) uniform sampler2D u_specular_tex;        // a
layout(binding = 22) uniform sampler2D u_specular_color_tex;  // rgb, sRGB
uniform vec4 u_specular_layer;  // colour factor, specular factor
#endif
#ifdef FEATURE_ANISOTROPY
layout(binding = 25) uniform sampler2D u_anisotropy_tex;  // rg direction (tangent space), b strength
uniform vec2 u_anisotropy;  // strength, rotation (radians, counter-clockwise in tangent space)
#endif
#ifdef FEATURE_IRIDESCENCE
layout(binding = 26) uniform sampler2D u_iridescence_tex;            // r
layout(binding = 27) uniform sampler2D u_iridescence_thickness_tex;  // g
uniform vec4 u_iridescence;  // factor, film ior, thickness minimum, maximum (nm)
#endif
uniform float u_ior;   // KHR_materials_ior (1.5 without): F0, and the refraction of transmission
uniform bool u_blend;  // alphaMode BLEND: the forward pass composites by alpha (else opaque)
#ifdef FEATURE_TRANSMISSION
layout(binding = 23) uniform sampler2D u_transmission_tex;  // r
layout(binding = 24) uniform sampler2D u_thickness_tex;     // g
uniform vec4 u_transmission;       // factor, thickness (mesh units), attenuation distance (0: none)
uniform vec3 u_attenuation_color;
#endif
bool has_ext_tex(int slot) { return (u_ext_tex & (1 << (slot - SLOT_CLEARCOAT))) != 0; }

// The interpolated vertex attributes at the point.
struct SurfacePoint {
  vec3 normal;   // world space, not normalised
  vec4 tangent;  // world xyz, handedness w
  vec2 uv0, uv1;
  vec4 color;
  bool front_facing;
};

vec4 sample_slot(sampler2D tex, int slot, vec2 uv);

vec2 slot_uv(int slot, SurfacePoint s) { return (u_uv_matrix[slot] * vec3(u_uv_set[slot] == 1 ? s.uv1 : s.uv0, 1.0)).xy; }

// Base colour and alpha (what the alpha mask tests).
vec4 material_base(SurfacePoint s) {
  vec4 base = u_base_color * s.color;
  if (u_has_tex.x != 0) base *= sample_slot(u_base_color_tex, SLOT_BASE, slot_uv(SLOT_BASE, s));
  return base;
}

bool material_masked_out(vec4 base) { return u_alpha_cutoff >= 0.0 && base.a < u_alpha_cutoff; }

// A tangent-space normal map texel (0..1) applied to geometric normal n.
vec3 perturbed_normal(vec3 n, vec4 tangent, vec3 texel, float scale) {
  vec3 t = normalize(tangent.xyz - n * dot(n, tangent.xyz));
  vec3 b = cross(n, t) * tangent.w;
  vec3 m = texel * 2.0 - 1.0;
  m.xy *= scale;
  return normalize(mat3(t, b, n) * m);
}

GBufferTexel evaluate_material(SurfacePoint s, vec4 base) {
  vec3 geometric = normalize(s.normal);
  if (u_double_sided && !s.front_facing) geometric = -geometric;
  vec3 n = geometric;
  if (u_has_tex.z != 0)
    n = perturbed_normal(geometric, s.tangent, sample_slot(u_normal_tex, SLOT_NORMAL, slot_uv(SLOT_NORMAL, s)).xyz, u_normal_scale);
  float metallic = u_metallic, roughness = u_roughness, occlusion = 1.0;
  if (u_spec_gloss) {
    vec4 sg = vec4(u_specular, u_glossiness);
    if (u_has_tex.y != 0) sg *= sample_slot(u_metal_rough_tex, SLOT_METAL_ROUGH, slot_uv(SLOT_METAL_ROUGH, s));
    MetalRough mr = spec_gloss_to_metal_rough(base.rgb, sg.rgb, sg.a);
    base.rgb = mr.base_color;
    metallic = mr.metallic;
    roughness = mr.roughness;
  } else if (u_has_tex.y != 0) {
    vec4 mr = sample_slot(u_metal_rough_tex, SLOT_METAL_ROUGH, slot_uv(SLOT_METAL_ROUGH, s));
    roughness *= mr.g;
    metallic *= mr.b;
  }
  if (u_has_tex.w != 0)
    occlusion = 1.0 + u_occlusion_strength * (sample_slot(u_occlusion_tex, SLOT_OCCLUSION, slot_uv(SLOT_OCCLUSION, s)).r - 1.0);
  vec3 emissive = u_emissive;
  if (u_has_emissive_tex) emissive *= sample_slot(u_emissive_tex, SLOT_EMISSIVE, slot_uv(SLOT_EMISSIVE, s)).rgb;

  GBufferTexel g;
  g.albedo = vec4(base.rgb, u_unlit ? 1.0 : 0.0);
  g.normal = vec4(encode_normal(n), 0.0, 0.0);
  g.material = vec4(metallic, roughness, occlusion, 0.0);
  g.emissive = vec4(emissive, 0.0);
#ifdef FEATURE_CLEARCOAT
  // KHR_materials_clearcoat: the coat's own normal map, else the geometric normal.
  vec3 cc = u_clearcoat;
  if (has_ext_tex(SLOT_CLEARCOAT)) cc.x *= sample_slot(u_clearcoat_tex, SLOT_CLEARCOAT, slot_uv(SLOT_CLEARCOAT, s)).r;
  if (has_ext_tex(SLOT_CLEARCOAT_ROUGHNESS))
    cc.y *= sample_slot(u_clearcoat_roughness_tex, SLOT_CLEARCOAT_ROUGHNESS, slot_uv(SLOT_CLEARCOAT_ROUGHNESS, s)).g;
  vec3 coat_n = geometric;
  if (has_ext_tex(SLOT_CLEARCOAT_NORMAL))
    coat_n = perturbed_normal(geometric, s.tangent,
                              sample_slot(u_clearcoat_normal_tex, SLOT_CLEARCOAT_NORMAL, slot_uv(SLOT_CLEARCOAT_NORMAL, s)).xyz, cc.z);
  g.clearcoat = vec4(cc.x, cc.y, encode_normal(coat_n));
#endif
#ifdef FEATURE_SHEEN
  vec4 sh = u_sheen;
  if (has_ext_tex(SLOT_SHEEN_COLOR)) sh.rgb *= sample_slot(u_sheen_color_tex, SLOT_SHEEN_COLOR, slot_uv(SLOT_SHEEN_COLOR, s)).rgb;
  if (has_ext_tex(SLOT_SHEEN_ROUGHNESS))
    sh.a *= sample_slot(u_sheen_roughness_tex, SLOT_SHEEN_ROUGHNESS, slot_uv(SLOT_SHEEN_ROUGHNESS, s)).a;
  g.sheen = sh;
#endif
#ifdef FEATURE_SPECULAR
  // KHR_materials_specular / _ior: F0 = min(((ior-1)/(ior+1))² · colour, 1) · specular, F90 = specular.
  vec3 tint = u_specular_layer.rgb;
  float weight = u_specular_layer.a;
  if (has_ext_tex(SLOT_SPECULAR_COLOR)) tint *= sample_slot(u_specular_color_tex, SLOT_SPECULAR_COLOR, slot_uv(SLOT_SPECULAR_COLOR, s)).rgb;
  if (has_ext_tex(SLOT_SPECULAR)) weight *= sample_slot(u_specular_tex, SLOT_SPECULAR, slot_uv(SLOT_SPECULAR, s)).a;
  float r = (u_ior - 1.0) / (u_ior + 1.0);
  vec3 f0 = min(r * r * tint, vec3(1.0)) * weight;
  g.specular = vec4(sqrt(f0), weight);
#endif
#ifdef FEATURE_IRIDESCENCE
  // KHR_materials_iridescence: factor and film thickness (the maximum without a texture).
  float film = u_iridescence.x, thickness_nm = u_iridescence.w;
  if (has_ext_tex(SLOT_IRIDESCENCE)) film *= sample_slot(u_iridescence_tex, SLOT_IRIDESCENCE, slot_uv(SLOT_IRIDESCENCE, s)).r;
  if (has_ext_tex(SLOT_IRIDESCENCE_THICKNESS))
    thickness_nm = mix(u_iridescence.z, u_iridescence.w,
                       sample_slot(u_iridescence_thickness_tex, SLOT_IRIDESCENCE_THICKNESS, slot_uv(SLOT_IRIDESCENCE_THICKNESS, s)).g);
  g.iridescence = vec4(film, clamp(thickness_nm / 2000.0, 0.0, 1.0), clamp((u_iridescence.y - 1.0) / 4.0, 0.0, 1.0), 0.0);
#endif
#ifdef FEATURE_ANISOTROPY
  // KHR_materials_anisotropy: the direction (tangent space, rotated) into world space
  // along the geometric tangent frame, and the strength.
  vec2 dir = vec2(1.0, 0.0);
  float strength = u_anisotropy.x;
  if (has_ext_tex(SLOT_ANISOTROPY)) {
    vec3 a = sample_slot(u_anisotropy_tex, SLOT_ANISOTROPY, slot_uv(SLOT_ANISOTROPY, s)).rgb;
    dir = a.rg * 2.0 - 1.0;
    strength *= a.b;
  }
  float rc = cos(u_anisotropy.y), rs = sin(u_anisotropy.y);
  dir = mat2(rc, rs, -rs, rc) * dir;
  vec3 tg = normalize(s.tangent.xyz - geometric * dot(geometric, s.tangent.xyz));
  vec3 bt = cross(geometric, tg) * s.tangent.w;
  g.anisotropy = vec4(strength, 0.0, encode_normal(normalize(mat3(tg, bt, geometric) * vec3(dir, 0.0))));
#endif
  return g;
}

#ifdef FEATURE_TRANSMISSION
// KHR_materials_transmission and _volume at the point (the forward pass alone reads it).
struct Transmission {
  float factor;     // of the dielectric's diffuse part that is transmitted
  float thickness;  // mesh units; 0: thin-walled
};
Transmission material_transmission(SurfacePoint s) {
  Transmission t = Transmission(u_transmission.x, u_transmission.y);
  if (has_ext_tex(SLOT_TRANSMISSION)) t.factor *= sample_slot(u_transmission_tex, SLOT_TRANSMISSION, slot_uv(SLOT_TRANSMISSION, s)).r;
  if (has_ext_tex(SLOT_THICKNESS)) t.thickness *= sample_slot(u_thickness_tex, SLOT_THICKNESS, slot_uv(SLOT_THICKNESS, s)).g;
  return t;
}
#endif

#ifndef LIGHTING_GLSL
#define LIGHTING_GLSL
// The light rig and the surface response: one implementation for the deferred lighting
// pass (lighting.frag, on a G-buffer texel) and the forward pass of alphaMode BLEND
// surfaces (blend.frag, at a fragment). The includer binds the shadow map to unit 5 and
// the Lights block to binding 0.
#include "common/gbuffer_texel.glsl"
layout(binding = 5) uniform sampler2DShadow u_shadow_map;
#ifdef FEATURE_SHEEN
// The Charlie sheen lobe's directional albedo E(n·v, sheen roughness) (sheen_albedo.hpp).
layout(binding = 11) uniform sampler2D u_sheen_albedo;
#endif

const int MAX_POINT_LIGHTS = 64;
const int MAX_FILE_LIGHTS = 64;
layout(std140, binding = 0) uniform Lights {
  vec4 u_point_pos_range[MAX_POINT_LIGHTS];  // world xyz, range
  vec4 u_point_color[MAX_POINT_LIGHTS];      // linear rgb × intensity
  vec4 u_sun_dir;                            // towards the light
  vec4 u_sun_color;
  vec4 u_ambient;                            // rgb, w = exposure
  vec4 u_background;
  mat4 u_sun_matrix;                         // world -> shadow map [0,1]³
  ivec4 u_counts;                            // x: point lights, y: shadow on, z: file lights
  // KHR_lights_punctual (light_rig.hpp, make_scene_lights); the rig's members are unused then.
  vec4 u_light_pos_range[MAX_FILE_LIGHTS];   // world xyz, range (0: no cutoff)
  vec4 u_light_color[MAX_FILE_LIGHTS];       // rgb × intensity, w: 0 directional, 1 point/spot
  vec4 u_light_dir[MAX_FILE_LIGHTS];         // where it shines, w: cone scale
  vec4 u_light_cone[MAX_FILE_LIGHTS];        // x: cone offset
};

// Per-tile light lists (light_tiles.hpp): (first, count) per tile of u_light_grid.z
// pixels, then light indices; u_light_grid.w == 0: every file light at every sample.
layout(binding = 7) uniform usamplerBuffer u_light_tiles;
uniform ivec4 u_light_grid;  // columns, rows, tile pixels, lists on

const float PI = 3.14159265359;

float d_ggx(float n_dot_h, float a) {
  float a2 = a * a;
  float d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
  return a2 / (PI * d * d);
}

// Height-correlated Smith visibility (includes the 1 / (4 n·l n·v) term).
float v_smith(float n_dot_v, float n_dot_l, float a) {
  float a2 = a * a;
  float gv = n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2);
  float gl = n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2);
  return 0.5 / max(gv + gl, 1e-5);
}

#ifdef FEATURE_SHEEN
// KHR_materials_sheen: Charlie distribution (α = roughness², kept above 1e-3 as the
// albedo table is) and Neubelt's visibility, which the specification allows.
float sheen_alpha(float roughness) { return max(roughness * roughness, 1e-3); }
float d_charlie(float n_dot_h, float alpha) {
  float inv = 1.0 / alpha;
  float sin2 = max(1.0 - n_dot_h * n_dot_h, 0.0);
  return (2.0 + inv) * pow(sin2, 0.5 * inv) / (2.0 * PI);
}
float v_neubelt(float n_dot_v, float n_dot_l) { return 1.0 / (4.0 * (n_dot_l + n_dot_v - n_dot_l * n_dot_v)); }
// What the sheen layer leaves of the base below it: 1 − max(sheen colour) · E(n·v).
float sheen_scaling(Surface s, float n_dot_v) {
  float e = texture(u_sheen_albedo, vec2(n_dot_v, s.sheen_roughness)).r;
  return 1.0 - max(s.sheen_color.r, max(s.sheen_color.g, s.sheen_color.b)) * e;
}
#endif
#ifdef FEATURE_CLEARCOAT
// KHR_materials_clearcoat's Fresnel: ior 1.5 (F0 0.04) at the coat normal.
float coat_fresnel(Surface s, vec3 v) { return 0.04 + 0.96 * pow(1.0 - clamp(dot(s.clearcoat_normal, v), 0.0, 1.0), 5.0); }
#endif

#ifdef FEATURE_ANISOTROPY
// KHR_materials_anisotropy: GGX stretched along t (α_t = mix(α, 1, strength²)), α_b = α.
float d_ggx_anisotropic(float n_dot_h, float t_dot_h, float b_dot_h, float at, float ab) {
  float a2 = at * ab;
  vec3 f = vec3(ab * t_dot_h, at * b_dot_h, a2 * n_dot_h);
  float w2 = a2 / dot(f, f);
  return a2 * w2 * w2 / PI;
}
float v_smith_anisotropic(float n_dot_l, float n_dot_v, vec3 tbv, vec3 tbl, float at, float ab) {
  float gv = n_dot_l * length(vec3(at * tbv.x, ab * tbv.y, n_dot_v));
  float gl = n_dot_v * length(vec3(at * tbl.x, ab * tbl.y, n_dot_l));
  return clamp(0.5 / max(gv + gl, 1e-5), 0.0, 1.0);
}
#endif

#ifdef FEATURE_IRIDESCENCE
// KHR_materials_iridescence: the thin-film Fresnel of Belcour and Barla (2017, "A
// Practical Extension to Microfacet Theory for the Modeling of Varying Iridescence") as
// the specification's reference does it: a film of index eta and thickness d (nm) over a
// base whose index follows from its F0; the Airy sum's orders 0-2, each order's
// interference integrated against the CIE 1931 sensitivities in Fourier space (the
// paper's Gaussian fit), then XYZ to linear Rec. 709.
vec3 film_sensitivity(float opd_nm, vec3 shift) {
  float phase = 2.0 * PI * opd_nm * 1e-9;
  const vec3 amplitude = vec3(5.4856e-13, 4.4201e-13, 5.2481e-13);
  const vec3 centre = vec3(1.6810e+06, 1.7953e+06, 2.2084e+06);
  const vec3 variance = vec3(4.3278e+09, 9.3046e+09, 6.6121e+09);
  vec3 xyz = amplitude * sqrt(2.0 * PI * variance) * cos(centre * phase + shift) * exp(-phase * phase * variance);
  xyz.x += 9.7470e-14 * sqrt(2.0 * PI * 4.5282e+09) * cos(2.2399e+06 * phase + shift.x) * exp(-4.5282e+09 * phase * phase);
  const mat3 xyz_to_rec709 = mat3(3.2404542, -0.9692660, 0.0556434, -1.5371385, 1.8760108, -0.2040259, -0.4985314, 0.0415560, 1.0572252);
  return xyz_to_rec709 * (xyz / 1.0685e-7);
}

vec3 film_fresnel(float cos1, float film_ior, float thickness_nm, vec3 base_f0) {
  float eta = mix(1.0, film_ior, smoothstep(0.0, 0.03, thickness_nm));  // no film at thickness 0
  float cos2_sq = 1.0 - (1.0 - cos1 * cos1) / (eta * eta);
  if (cos2_sq < 0.0) return vec3(1.0);  // total internal reflection
  float cos2 = sqrt(cos2_sq);
  // Air to film: Schlick's reflectance, its transmission and phase change.
  float r0 = (eta - 1.0) / (eta + 1.0);
  float r12 = r0 * r0 + (1.0 - r0 * r0) * pow(1.0 - cos1, 5.0);
  float t121 = 1.0 - r12;
  float phi21 = eta < 1.0 ? 0.0 : PI;
  // Film to base.
  vec3 root = sqrt(clamp(base_f0, 0.0, 0.9999));
  vec3 base_eta = (1.0 + root) / (1.0 - root);
  vec3 r1 = (base_eta - eta) / (base_eta + eta);
  vec3 r23 = r1 * r1 + (1.0 - r1 * r1) * pow(1.0 - cos2, 5.0);
  vec3 phi23 = mix(vec3(0.0), vec3(PI), lessThan(base_eta, vec3(eta)));
  // The Airy sum: the DC term, then orders 1 and 2 with their spectral interference.
  float opd = 2.0 * eta * thickness_nm * cos2;
  vec3 phi = vec3(phi21) + phi23;
  vec3 r123 = clamp(r12 * r23, 1e-5, 0.9999);
  vec3 rs = t121 * t121 * r23 / (1.0 - r123);
  vec3 sum = r12 + rs;
  vec3 cm = rs - t121;
  for (int m = 1; m <= 2; ++m) {
    cm *= sqrt(r123);
    sum += cm * 2.0 * film_sensitivity(float(m) * opd, float(m) * phi);
  }
  return max(sum, vec3(0.0));  // out-of-gamut colours clamp at 0
}
#endif

// The BRDF times n·l for light from l: metal-roughness GGX with the dielectric F0/F90
// of KHR_materials_specular, under the sheen and clearcoat layers when the scene has them
// (docs/scenes.md, "Materials").
vec3 shade(vec3 n, vec3 v, vec3 l, Surface s) {
  float n_dot_l = dot(n, l);
  vec3 color = vec3(0.0);
  // Everything per light stays inside the test: lights behind the surface (most of a
  // room's 64) cost one dot product, as in the plain metal-rough shader before the layers.
  if (n_dot_l > 0.0) {
    vec3 h = normalize(v + l);
    float n_dot_v = max(dot(n, v), 1e-4), n_dot_h = max(dot(n, h), 0.0), v_dot_h = max(dot(v, h), 0.0);
    float a = max(s.roughness * s.roughness, 2e-3);
#ifdef FEATURE_SPECULAR
    vec3 f0 = mix(s.f0, s.albedo, s.metallic);
    float f90 = mix(s.f90, 1.0, s.metallic);
#else
    vec3 f0 = mix(vec3(0.04), s.albedo, s.metallic);  // ior 1.5
    const float f90 = 1.0;
#endif
    vec3 f = f0 + (f90 - f0) * pow(1.0 - v_dot_h, 5.0);
#ifdef FEATURE_IRIDESCENCE
    f = mix(f, s.film_fresnel, s.iridescence);
#endif
    vec3 specular = d_ggx(n_dot_h, a) * v_smith(n_dot_v, n_dot_l, a) * f;
#ifdef FEATURE_ANISOTROPY
    if (s.anisotropy > 0.0) {
      vec3 t = normalize(s.anisotropy_direction - n * dot(n, s.anisotropy_direction));
      vec3 b = cross(n, t);
      float at = mix(a, 1.0, s.anisotropy * s.anisotropy);
      specular = d_ggx_anisotropic(n_dot_h, dot(t, h), dot(b, h), at, a) *
                 v_smith_anisotropic(n_dot_l, n_dot_v, vec3(dot(t, v), dot(b, v), 0.0), vec3(dot(t, l), dot(b, l), 0.0), at, a) * f;
    }
#endif
    vec3 diffuse = (1.0 - f) * (1.0 - s.metallic) * s.albedo / PI;
#ifdef FEATURE_TRANSMISSION
    diffuse *= 1.0 - s.transmission;  // what is transmitted is not diffused (the forward pass adds it)
#endif
    color = diffuse + specular;
#ifdef FEATURE_SHEEN
    color = color * sheen_scaling(s, n_dot_v) +
            s.sheen_color * d_charlie(n_dot_h, sheen_alpha(s.sheen_roughness)) * v_neubelt(n_dot_v, n_dot_l);
#endif
    color *= n_dot_l;
  }
#ifdef FEATURE_CLEARCOAT
  if (s.clearcoat > 0.0) {
    vec3 nc = s.clearcoat_normal;
    float fc = coat_fresnel(s, v);
    color *= 1.0 - s.clearcoat * fc;
    float c_dot_l = dot(nc, l);
    if (c_dot_l > 0.0) {
      float ac = max(s.clearcoat_roughness * s.clearcoat_roughness, 2e-3);
      float c_dot_v = max(dot(nc, v), 1e-4);
      vec3 h = normalize(v + l);
      color += s.clearcoat * fc * d_ggx(max(dot(nc, h), 0.0), ac) * v_smith(c_dot_v, c_dot_l, ac) * c_dot_l;
    }
  }
#endif
  return color;
}

float sun_visibility(vec3 p, vec3 n) {
  if (u_counts.y == 0) return 1.0;
  vec4 s = u_sun_matrix * vec4(p + n * 0.002 * u_sun_color.w, 1.0);
  if (any(lessThan(s.xyz, vec3(0.0))) || any(greaterThan(s.xyz, vec3(1.0)))) return 1.0;
  vec2 texel = 1.0 / vec2(textureSize(u_shadow_map, 0));
  float bias = 0.0015;
  float sum = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) sum += texture(u_shadow_map, vec3(s.xy + vec2(x, y) * texel, s.z - bias));
  return sum / 9.0;
}

// What a file light adds at p: radiance for intensity in cd (point, spot: E = I / d²
// at normal incidence) or lux (directional: E = I), with the glTF specification's range
// window max(min(1 − (d/range)⁴, 1), 0) and spot cone sat(cos θ · scale + offset)².
vec3 file_light(int i, vec3 p, vec3 n, vec3 v, Surface s) {
  vec4 c = u_light_color[i];
  if (c.w == 0.0) return shade(n, v, -u_light_dir[i].xyz, s) * c.rgb;
  vec3 to_light = u_light_pos_range[i].xyz - p;
  float d2 = max(dot(to_light, to_light), 1e-8);
  float range = u_light_pos_range[i].w;
  float window = 1.0;
  if (range > 0.0) {
    float r = d2 / (range * range);  // (d/range)²
    window = clamp(1.0 - r * r, 0.0, 1.0);
    if (window == 0.0) return vec3(0.0);
  }
  vec3 l = to_light * inversesqrt(d2);
  float cone = clamp(dot(u_light_dir[i].xyz, -l) * u_light_dir[i].w + u_light_cone[i].x, 0.0, 1.0);
  cone *= cone;
  if (cone == 0.0) return vec3(0.0);
  return shade(n, v, l, s) * c.rgb * (window * cone / d2);
}

// ACES filmic fit (Narkowicz 2015), display-referred linear output.
vec3 tone_map(vec3 x) {
  return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

// Tone-mapped colour of a lit surface point p (world) with normal n seen from the camera,
// at the eye's screen pixel `pixel` (for the tile's light list).
vec3 lit_color(ivec2 pixel, vec3 p, vec3 n, vec3 camera_pos, Surface s) {
  vec3 v = normalize(camera_pos - p);
#ifdef FEATURE_IRIDESCENCE
  if (s.iridescence > 0.0)
    s.film_fresnel = film_fresnel(clamp(dot(n, v), 0.0, 1.0), s.film_ior, s.film_thickness_nm, mix(s.f0, s.albedo, s.metallic));
#endif
  // Ambient: diffuse for dielectrics, a flat specular (F0) so metals are not black.
  vec3 f0 = mix(s.f0, s.albedo, s.metallic);
#ifdef FEATURE_IRIDESCENCE
  f0 = mix(f0, s.film_fresnel, s.iridescence);  // the film's colour in the ambient reflection too
#endif
  float diffuse_weight = 1.0 - s.metallic;
#ifdef FEATURE_TRANSMISSION
  diffuse_weight *= 1.0 - s.transmission;
#endif
  vec3 color = u_ambient.rgb * (s.albedo * diffuse_weight + f0) * s.occlusion;
#ifdef FEATURE_SHEEN
  float e = texture(u_sheen_albedo, vec2(max(dot(n, v), 0.0), s.sheen_roughness)).r;
  color = color * sheen_scaling(s, max(dot(n, v), 0.0)) + u_ambient.rgb * s.sheen_color * e * s.occlusion;
#endif
  vec3 emissive = s.emissive;
#ifdef FEATURE_CLEARCOAT
  // The coat dims what is below it, emission included, and reflects the ambient at F_c.
  float coat = s.clearcoat * coat_fresnel(s, v);
  color = color * (1.0 - coat) + u_ambient.rgb * coat * s.occlusion;
  emissive *= 1.0 - coat;
#endif
#ifdef FILE_LIGHTS
  // The file's KHR_lights_punctual lights (the compositor compiles this for a scene that
  // has them, the rig below for one that has none).
  if (u_light_grid.w != 0) {
    ivec2 t = clamp(pixel / u_light_grid.z, ivec2(0), u_light_grid.xy - 1);
    int k = t.y * u_light_grid.x + t.x;
    int first = int(texelFetch(u_light_tiles, 2 * k).r), count = int(texelFetch(u_light_tiles, 2 * k + 1).r);
    for (int j = 0; j < count; ++j) color += file_light(int(texelFetch(u_light_tiles, first + j).r), p, n, v, s);
  } else {
    for (int i = 0; i < u_counts.z; ++i) color += file_light(i, p, n, v, s);
  }
#else
  // The rig: its sun, then its point lights.
  color += shade(n, v, u_sun_dir.xyz, s) * u_sun_color.rgb * sun_visibility(p, n);
  for (int i = 0; i < u_counts.x; ++i) {
    vec3 to_light = u_point_pos_range[i].xyz - p;
    float range = u_point_pos_range[i].w;
    float d2 = dot(to_light, to_light);
    if (d2 >= range * range) continue;
    float x = d2 / (range * range);
    float window = (1.0 - x * x) * (1.0 - x * x);
    float falloff = window / (1.0 + 16.0 * x);
    color += shade(n, v, to_light * inversesqrt(d2), s) * u_point_color[i].rgb * falloff;
  }
#endif
  color += emissive;
  return tone_map(color * u_ambient.w);
}
#endif

// KHR_materials_pbrSpecularGlossiness -> metal-roughness, per fragment. The metallic
// value solves for the metalness that reproduces the specular colour's brightness over
// the dielectric F0 of 0.04 (the conversion of Khronos's glTF sample tools and
// BabylonJS); roughness = 1 - glossiness. Formulas in docs/scenes.md.
struct MetalRough {
  vec3 base_color;
  float metallic;
  float roughness;
};

const float kDielectricF0 = 0.04;

float perceived_brightness(vec3 c) { return sqrt(0.299 * c.r * c.r + 0.587 * c.g * c.g + 0.114 * c.b * c.b); }

float solve_metallic(float diffuse, float specular, float one_minus_specular_strength) {
  if (specular < kDielectricF0) return 0.0;
  float a = kDielectricF0;
  float b = diffuse * one_minus_specular_strength / (1.0 - kDielectricF0) + specular - 2.0 * kDielectricF0;
  float c = kDielectricF0 - specular;
  float d = max(b * b - 4.0 * a * c, 0.0);
  return clamp((-b + sqrt(d)) / (2.0 * a), 0.0, 1.0);
}

MetalRough spec_gloss_to_metal_rough(vec3 diffuse, vec3 specular, float glossiness) {
  float one_minus_strength = 1.0 - max(specular.r, max(specular.g, specular.b));
  float m = solve_metallic(perceived_brightness(diffuse), perceived_brightness(specular), one_minus_strength);
  vec3 from_diffuse = diffuse * one_minus_strength / (1.0 - kDielectricF0) / max(1.0 - m, 1e-4);
  vec3 from_specular = (specular - kDielectricF0 * (1.0 - m)) / max(m, 1e-4);
  vec3 base = clamp(mix(from_diffuse, from_specular, m * m), 0.0, 1.0);
  return MetalRough(base, m, clamp(1.0 - glossiness, 0.0, 1.0));
}

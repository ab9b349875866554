#include "gltf_materials.hpp"

#include <cmath>
#include <functional>

#include <glm/common.hpp>

namespace foveal::render::detail {

glm::mat3 texture_transform_matrix(glm::vec2 offset, float rotation, glm::vec2 scale) {
  const float c = std::cos(rotation), s = std::sin(rotation);
  // Columns of T * R * S, R = [c s; -s c] as the extension defines it.
  return glm::mat3(glm::vec3(c * scale.x, -s * scale.x, 0.0f), glm::vec3(s * scale.y, c * scale.y, 0.0f),
                   glm::vec3(offset, 1.0f));
}

namespace {

// A texture reference as the loader needs it, from either tinygltf's typed TextureInfo
// or the untyped JSON of an extension (spec-gloss keeps its textures there).
struct TextureRef {
  int index = -1;
  int tex_coord = 0;
  const tinygltf::ExtensionMap* extensions = nullptr;  // typed form
  const tinygltf::Value* value = nullptr;              // untyped form
};

double number(const tinygltf::Value& v, const char* key, double fallback) {
  if (!v.IsObject() || !v.Has(key) || !v.Get(key).IsNumber()) return fallback;
  return v.Get(key).GetNumberAsDouble();
}

// Reads `n` numbers of array `key` into `out` when present and well-formed.
template <class Vec>
bool numbers(const tinygltf::Value& v, const char* key, int n, Vec& out) {
  if (!v.IsObject() || !v.Has(key)) return false;
  const tinygltf::Value& a = v.Get(key);
  if (!a.IsArray() || static_cast<int>(a.ArrayLen()) != n) return false;
  for (int i = 0; i < n; ++i)
    if (!a.Get(i).IsNumber()) return false;
  for (int i = 0; i < n; ++i) out[i] = static_cast<float>(a.Get(i).GetNumberAsDouble());
  return true;
}

const tinygltf::Value* transform_of(const TextureRef& t) {
  if (t.extensions) {
    auto it = t.extensions->find("KHR_texture_transform");
    return it == t.extensions->end() ? nullptr : &it->second;
  }
  if (t.value && t.value->Has("extensions") && t.value->Get("extensions").Has("KHR_texture_transform"))
    return &t.value->Get("extensions").Get("KHR_texture_transform");
  return nullptr;
}

TextureUv texture_uv(const TextureRef& t, const std::string& where, std::vector<std::string>& warnings) {
  TextureUv uv;
  int set = t.tex_coord;
  if (const tinygltf::Value* x = transform_of(t)) {
    glm::vec2 offset(0.0f), scale(1.0f);
    numbers(*x, "offset", 2, offset);
    numbers(*x, "scale", 2, scale);
    uv.matrix = texture_transform_matrix(offset, static_cast<float>(number(*x, "rotation", 0.0)), scale);
    set = static_cast<int>(number(*x, "texCoord", set));
  }
  if (set != 0 && set != 1) {
    warnings.push_back(where + ": a texture reads TEXCOORD_" + std::to_string(set) +
                       "; foveal reads TEXCOORD_0 and TEXCOORD_1 only and uses TEXCOORD_0");
    set = 0;
  }
  uv.set = set;
  return uv;
}

TextureRef ref(const tinygltf::TextureInfo& t) { return {t.index, t.texCoord, &t.extensions, nullptr}; }
TextureRef ref(const tinygltf::NormalTextureInfo& t) { return {t.index, t.texCoord, &t.extensions, nullptr}; }
TextureRef ref(const tinygltf::OcclusionTextureInfo& t) { return {t.index, t.texCoord, &t.extensions, nullptr}; }
TextureRef ref(const tinygltf::Value& ext, const char* key) {
  if (!ext.Has(key) || !ext.Get(key).IsObject()) return {};
  const tinygltf::Value& v = ext.Get(key);
  return {static_cast<int>(number(v, "index", -1)), static_cast<int>(number(v, "texCoord", 0)), nullptr, &v};
}

// A factor of an extension in [lo, hi]: out-of-range values are clamped, with a warning.
float factor(const tinygltf::Value& ext, const char* key, double fallback, double lo, double hi, const std::string& where,
             std::vector<std::string>& warnings) {
  const double v = number(ext, key, fallback);
  if (v >= lo && v <= hi) return static_cast<float>(v);
  warnings.push_back(where + ": " + key + " " + std::to_string(v) + " is outside [" + std::to_string(lo) + ", " +
                     std::to_string(hi) + "]; clamped");
  return static_cast<float>(v < lo ? lo : hi);
}

using SlotReader = std::function<Status(const TextureRef&, bool srgb, Material::Slot, int&)>;

// KHR_materials_clearcoat, _sheen, _specular and _ior: factors, textures and the
// feature bits the compositor's shader variant is chosen by (docs/scenes.md, "Materials").
Status read_material_layers(const tinygltf::Material& gm, const std::string& where, std::vector<std::string>& warnings,
                            Material& mat, const SlotReader& tex) {
  auto read = [&](const tinygltf::Value& ext, const char* key, bool srgb, Material::Slot slot) {
    return tex(ref(ext, key), srgb, slot, mat.ext_tex[static_cast<std::size_t>(slot - Material::kCoreSlots)]);
  };
  auto find = [&](const char* name) -> const tinygltf::Value* {
    auto it = gm.extensions.find(name);
    return it == gm.extensions.end() ? nullptr : &it->second;
  };
  constexpr double kLarge = 1e6;
  if (const tinygltf::Value* cc = find("KHR_materials_clearcoat")) {
    const std::string at = where + ".extensions.KHR_materials_clearcoat";
    mat.clearcoat = factor(*cc, "clearcoatFactor", 0.0, 0.0, 1.0, at, warnings);
    mat.clearcoat_roughness = factor(*cc, "clearcoatRoughnessFactor", 0.0, 0.0, 1.0, at, warnings);
    if (cc->Has("clearcoatNormalTexture"))
      mat.clearcoat_normal_scale = static_cast<float>(number(cc->Get("clearcoatNormalTexture"), "scale", 1.0));
    if (Status s = read(*cc, "clearcoatTexture", false, Material::clearcoat_slot); !s) return s;
    if (Status s = read(*cc, "clearcoatRoughnessTexture", false, Material::clearcoat_roughness_slot); !s) return s;
    if (Status s = read(*cc, "clearcoatNormalTexture", false, Material::clearcoat_normal_slot); !s) return s;
    if (mat.clearcoat > 0.0f) mat.features |= feature_clearcoat;  // a zero factor is no coat, texture or not
  }
  if (const tinygltf::Value* sh = find("KHR_materials_sheen")) {
    const std::string at = where + ".extensions.KHR_materials_sheen";
    glm::vec3 color(0.0f);
    numbers(*sh, "sheenColorFactor", 3, color);
    mat.sheen_color = glm::clamp(color, glm::vec3(0.0f), glm::vec3(1.0f));
    mat.sheen_roughness = factor(*sh, "sheenRoughnessFactor", 0.0, 0.0, 1.0, at, warnings);
    if (Status s = read(*sh, "sheenColorTexture", true, Material::sheen_color_slot); !s) return s;
    if (Status s = read(*sh, "sheenRoughnessTexture", false, Material::sheen_roughness_slot); !s) return s;
    if (glm::max(mat.sheen_color.r, glm::max(mat.sheen_color.g, mat.sheen_color.b)) > 0.0f) mat.features |= feature_sheen;
  }
  if (const tinygltf::Value* sp = find("KHR_materials_specular")) {
    const std::string at = where + ".extensions.KHR_materials_specular";
    mat.specular_factor = factor(*sp, "specularFactor", 1.0, 0.0, 1.0, at, warnings);
    glm::vec3 color(1.0f);
    numbers(*sp, "specularColorFactor", 3, color);
    mat.specular_color = glm::clamp(color, glm::vec3(0.0f), glm::vec3(static_cast<float>(kLarge)));
    if (Status s = read(*sp, "specularTexture", false, Material::specular_slot); !s) return s;
    if (Status s = read(*sp, "specularColorTexture", true, Material::specular_color_slot); !s) return s;
    mat.features |= feature_specular;
  }
  if (const tinygltf::Value* tr = find("KHR_materials_transmission")) {
    mat.transmission = factor(*tr, "transmissionFactor", 0.0, 0.0, 1.0, where + ".extensions.KHR_materials_transmission", warnings);
    if (Status s = read(*tr, "transmissionTexture", false, Material::transmission_slot); !s) return s;
    if (mat.transmission > 0.0f) mat.features |= feature_transmission;
  }
  if (const tinygltf::Value* vo = find("KHR_materials_volume")) {
    const std::string at = where + ".extensions.KHR_materials_volume";
    mat.thickness = factor(*vo, "thicknessFactor", 0.0, 0.0, kLarge, at, warnings);
    // The specification's default distance is +infinity: no attenuation, held as 0 here.
    if (vo->Has("attenuationDistance"))
      mat.attenuation_distance = factor(*vo, "attenuationDistance", 0.0, 1e-6, kLarge, at, warnings);
    glm::vec3 color(1.0f);
    numbers(*vo, "attenuationColor", 3, color);
    mat.attenuation_color = glm::clamp(color, glm::vec3(0.0f), glm::vec3(1.0f));
    if (Status s = read(*vo, "thicknessTexture", false, Material::thickness_slot); !s) return s;
    if (!find("KHR_materials_transmission"))
      warnings.push_back(at + ": a volume without KHR_materials_transmission is drawn as its surface only");
  }
  if (const tinygltf::Value* an = find("KHR_materials_anisotropy")) {
    const std::string at = where + ".extensions.KHR_materials_anisotropy";
    mat.anisotropy = factor(*an, "anisotropyStrength", 0.0, 0.0, 1.0, at, warnings);
    mat.anisotropy_rotation = static_cast<float>(number(*an, "anisotropyRotation", 0.0));
    if (!std::isfinite(mat.anisotropy_rotation)) mat.anisotropy_rotation = 0.0f;
    if (Status s = read(*an, "anisotropyTexture", false, Material::anisotropy_slot); !s) return s;
    if (mat.anisotropy > 0.0f) mat.features |= feature_anisotropy;
  }
  if (const tinygltf::Value* ir = find("KHR_materials_iridescence")) {
    const std::string at = where + ".extensions.KHR_materials_iridescence";
    mat.iridescence = factor(*ir, "iridescenceFactor", 0.0, 0.0, 1.0, at, warnings);
    mat.iridescence_ior = factor(*ir, "iridescenceIor", 1.3, 1.0, 10.0, at, warnings);
    mat.iridescence_thickness_min = factor(*ir, "iridescenceThicknessMinimum", 100.0, 0.0, 1e5, at, warnings);
    mat.iridescence_thickness_max = factor(*ir, "iridescenceThicknessMaximum", 400.0, 0.0, 1e5, at, warnings);
    if (Status s = read(*ir, "iridescenceTexture", false, Material::iridescence_slot); !s) return s;
    if (Status s = read(*ir, "iridescenceThicknessTexture", false, Material::iridescence_thickness_slot); !s) return s;
    if (mat.iridescence > 0.0f) mat.features |= feature_iridescence;
  }
  if (const tinygltf::Value* io = find("KHR_materials_ior")) {
    mat.ior = factor(*io, "ior", 1.5, 1.0, kLarge, where + ".extensions.KHR_materials_ior", warnings);
    mat.features |= feature_specular;
  }
  return {};
}

}  // namespace

Result<Material> read_material(const tinygltf::Material& gm, const TextureUploader& upload, const std::string& where,
                               std::vector<std::string>& warnings) {
  Material mat;
  const auto& pbr = gm.pbrMetallicRoughness;
  for (int i = 0; i < 4; ++i) mat.base_color[i] = static_cast<float>(pbr.baseColorFactor[static_cast<std::size_t>(i)]);
  mat.metallic = static_cast<float>(pbr.metallicFactor);
  mat.roughness = static_cast<float>(pbr.roughnessFactor);
  for (int i = 0; i < 3 && i < static_cast<int>(gm.emissiveFactor.size()); ++i)
    mat.emissive[i] = static_cast<float>(gm.emissiveFactor[static_cast<std::size_t>(i)]);
  if (auto it = gm.extensions.find("KHR_materials_emissive_strength"); it != gm.extensions.end())
    mat.emissive *= static_cast<float>(number(it->second, "emissiveStrength", 1.0));
  mat.normal_scale = static_cast<float>(gm.normalTexture.scale);
  mat.occlusion_strength = static_cast<float>(gm.occlusionTexture.strength);
  mat.double_sided = gm.doubleSided;
  if (gm.alphaMode == "MASK") mat.alpha_cutoff = static_cast<float>(gm.alphaCutoff);
  else if (gm.alphaMode == "BLEND") mat.blend = true;  // any other value was refused by the JSON checks
  mat.unlit = gm.extensions.count("KHR_materials_unlit") > 0;

  auto tex = [&](const TextureRef& t, bool srgb, Material::Slot slot, int& out) -> Status {
    auto r = upload(t.index, srgb);
    if (!r) return r.error();
    out = *r;
    if (out >= 0) mat.uv[slot] = texture_uv(t, where, warnings);
    return {};
  };
  TextureRef base = ref(pbr.baseColorTexture), metal_rough = ref(pbr.metallicRoughnessTexture);
  bool metal_rough_srgb = false;
  if (auto it = gm.extensions.find("KHR_materials_pbrSpecularGlossiness"); it != gm.extensions.end()) {
    // The diffuse colour takes base colour's place; the specular (sRGB) + glossiness
    // texture takes metal-roughness's; the shader converts (shaders/common/spec_gloss.glsl).
    const tinygltf::Value& sg = it->second;
    mat.spec_gloss = true;
    mat.base_color = glm::vec4(1.0f);
    numbers(sg, "diffuseFactor", 4, mat.base_color);
    numbers(sg, "specularFactor", 3, mat.specular);
    mat.glossiness = static_cast<float>(number(sg, "glossinessFactor", 1.0));
    base = ref(sg, "diffuseTexture");
    metal_rough = ref(sg, "specularGlossinessTexture");
    metal_rough_srgb = true;
  }
  if (Status s = tex(base, true, Material::base_color_slot, mat.base_color_tex); !s) return s.error();
  if (Status s = tex(metal_rough, metal_rough_srgb, Material::metal_rough_slot, mat.metal_rough_tex); !s) return s.error();
  if (Status s = tex(ref(gm.normalTexture), false, Material::normal_slot, mat.normal_tex); !s) return s.error();
  if (Status s = tex(ref(gm.occlusionTexture), false, Material::occlusion_slot, mat.occlusion_tex); !s) return s.error();
  if (Status s = tex(ref(gm.emissiveTexture), true, Material::emissive_slot, mat.emissive_tex); !s) return s.error();
  if (mat.unlit) return mat;  // an unlit material has no layers to shade
  if (Status s = read_material_layers(gm, where, warnings, mat, tex); !s) return s.error();
  return mat;
}

}  // namespace foveal::render::detail

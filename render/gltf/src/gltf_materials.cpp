#include "gltf_materials.hpp"

#include <cmath>

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
  return mat;
}

}  // namespace foveal::render::detail

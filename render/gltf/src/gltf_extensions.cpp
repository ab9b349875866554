#include "gltf_extensions.hpp"

#include <algorithm>

namespace foveal::render::detail {

const std::vector<std::string>& supported_gltf_extensions() {
  static const std::vector<std::string> kSupported = {
      "EXT_mesh_gpu_instancing",        "EXT_meshopt_compression",            "KHR_draco_mesh_compression",
      "KHR_lights_punctual",
      "KHR_materials_anisotropy",       "KHR_materials_clearcoat",            "KHR_materials_emissive_strength",
      "KHR_materials_ior",              "KHR_materials_iridescence",
      "KHR_materials_pbrSpecularGlossiness", "KHR_materials_sheen",          "KHR_materials_specular",
      "KHR_materials_transmission",     "KHR_materials_unlit",                "KHR_materials_variants",
      "KHR_materials_volume",           "KHR_mesh_quantization",
      "KHR_texture_transform",
      // Metadata only: nothing in it changes the picture.
      "KHR_xmp",                        "KHR_xmp_json_ld",
  };
  return kSupported;
}

namespace {

bool supported(const std::string& ext) {
  const auto& s = supported_gltf_extensions();
  return std::find(s.begin(), s.end(), ext) != s.end();
}

std::string supported_list() {
  std::string out;
  for (const std::string& e : supported_gltf_extensions()) out += (out.empty() ? "" : ", ") + e;
  return out;
}

}  // namespace

Status check_gltf_extensions(const tinygltf::Model& model, const std::string& path, std::vector<std::string>& warnings) {
  for (const std::string& ext : model.extensionsRequired)
    if (!supported(ext))
      return Error{ErrorKind::unsupported,
                   path + ": requires extension " + ext + ", which foveal does not support (supported: " + supported_list() + ")"};
  for (const std::string& ext : model.extensionsUsed)
    if (!supported(ext)) warnings.push_back(path + ": uses extension " + ext + ", which foveal ignores");
  if (!model.animations.empty())
    warnings.push_back(path + ": " + std::to_string(model.animations.size()) + " animation(s) are not played (the rest pose is drawn)");
  if (!model.skins.empty()) warnings.push_back(path + ": skins are not applied (meshes are drawn unskinned)");
  const bool morphs = std::any_of(model.meshes.begin(), model.meshes.end(), [](const tinygltf::Mesh& m) {
    return std::any_of(m.primitives.begin(), m.primitives.end(), [](const tinygltf::Primitive& p) { return !p.targets.empty(); });
  });
  if (morphs) warnings.push_back(path + ": morph targets are not applied (base shapes are drawn)");
  return {};
}

}  // namespace foveal::render::detail

#pragma once
// glTF materials into foveal's Material: metal-roughness factors and textures, each
// texture's UV set and KHR_texture_transform, KHR_materials_emissive_strength,
// KHR_materials_unlit and KHR_materials_pbrSpecularGlossiness (docs/scenes.md).
#include <functional>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "foveal/core/error.hpp"
#include "foveal/render/scene_types.hpp"

namespace foveal::render::detail {

/// Uploads glTF texture `gltf_index` (-1: none) in sRGB or linear; returns its
/// Scene::textures index or -1.
using TextureUploader = std::function<Result<int>(int gltf_index, bool srgb)>;

/// The matrix uv' = M (u, v, 1) of KHR_texture_transform: translation * rotation * scale,
/// with the spec's rotation sense (counter-clockwise in UV space for positive angles).
glm::mat3 texture_transform_matrix(glm::vec2 offset, float rotation, glm::vec2 scale);

/// Material `gm` (named `where` in messages); warnings for what it asks that is ignored.
Result<Material> read_material(const tinygltf::Material& gm, const TextureUploader& upload, const std::string& where,
                               std::vector<std::string>& warnings);

}  // namespace foveal::render::detail

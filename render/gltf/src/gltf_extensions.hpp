#pragma once
// Which glTF extensions foveal reads, and what it says about the rest (docs/scenes.md).
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "foveal/core/error.hpp"

namespace foveal::render::detail {

/// The extensions the loader implements, sorted.
const std::vector<std::string>& supported_gltf_extensions();

/// An unsupported extension in extensionsRequired is an error naming it; one in
/// extensionsUsed only, and content foveal does not draw (animations, skins, morph
/// targets), each add one warning to `warnings`.
Status check_gltf_extensions(const tinygltf::Model& model, const std::string& path, std::vector<std::string>& warnings);

}  // namespace foveal::render::detail

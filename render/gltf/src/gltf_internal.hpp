#pragma once
// Shared by the glTF loader's parts (gltf_loader.cpp, gltf_json_checks.cpp,
// gltf_builder.cpp and the files it calls). CPU only.
#include <tiny_gltf.h>

#include <nlohmann/json.hpp>

#include "foveal/render/gltf_loader.hpp"

namespace foveal::render::detail {

/// What the loader has decoded so far, against GltfLimits::max_decoded_bytes.
class DecodeBudget {
 public:
  explicit DecodeBudget(std::size_t limit) : limit_(limit) {}
  /// Counts `bytes` more; an error naming `what` when that would pass the limit.
  Status take(std::size_t bytes, const std::string& what);

 private:
  std::size_t limit_, used_ = 0;
};

/// Checks the parts of the glTF JSON the renderer relies on, where their types are still
/// visible (tinygltf drops values of the wrong type without a word): every index in
/// range, transforms of the right size and finite, accessor, buffer view and buffer
/// fields of the right kind, the node hierarchy a forest. Messages: "FILE: PATH: what".
Status check_gltf_json(const nlohmann::json& root, const std::string& file);

/// Builds the scene from a model that passed check_gltf_json: every accessor read is
/// bounds-checked before its output is allocated; images must already be RGBA8.
Result<GltfScene> build_gltf_scene(const tinygltf::Model& model, const std::string& file, const GltfLimits& limits,
                                   DecodeBudget& budget, GltfSink& sink);

}  // namespace foveal::render::detail

#pragma once
// EXT_mesh_gpu_instancing: the transforms at which a node's mesh is drawn.
#include <cstddef>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "gltf_accessors.hpp"

namespace foveal::render::detail {

/// The node's mesh is drawn once per instance, at the node's transform times the
/// instance's T·R·S (attributes TRANSLATION, ROTATION (a unit quaternion, float or
/// normalised integers), SCALE; each optional, all of one count; custom "_..." attributes
/// are ignored). Without the extension: one, the identity. Each instance draws the mesh's
/// `primitives` as draw items of their own (no hardware instancing): with the scene's
/// `draws` so far, at most 2^20 in the scene. Node `n` is named `path` in messages.
Result<std::vector<glm::mat4>> node_instances(const tinygltf::Model& model, AccessorReader& read, const tinygltf::Node& n,
                                              const std::string& path, std::size_t primitives, std::size_t draws);

}  // namespace foveal::render::detail

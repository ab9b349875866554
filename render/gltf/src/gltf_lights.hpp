#pragma once
// KHR_lights_punctual: the lights' JSON checked where types are still visible, and each
// node's light placed by its world transform (docs/scenes.md, "Lights").
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "foveal/core/error.hpp"
#include "foveal/render/scene_types.hpp"

namespace foveal::render::detail {

/// The extension's `lights` (type, colour, intensity, range, spot cone angles:
/// finite, in the ranges the specification gives, 0 ≤ inner < outer ≤ π/2) and every
/// node's `light` index. Errors "FILE: extensions.KHR_lights_punctual.lights[2].range: ...";
/// a colour component above 1 is used as given with a warning.
Status check_gltf_lights(const nlohmann::json& root, const std::string& file, std::vector<std::string>& warnings);

/// The light node `node` (at `path`) carries, placed by `world`; nothing when it has
/// none. An error when a spot or directional light's direction has no length.
Result<std::vector<PunctualLight>> node_light(const tinygltf::Model& model, const tinygltf::Node& node, const glm::mat4& world,
                                              const std::string& file, const std::string& path);

}  // namespace foveal::render::detail

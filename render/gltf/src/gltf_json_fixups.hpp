#pragma once
// What tinygltf 2.7 (built without Draco) refuses although the extensions allow it:
// index accessors of Draco primitives without a buffer view, and meshopt fallback
// buffers without data. Both get placeholders in the JSON before tinygltf parses it;
// the placeholders are never read (gltf_decode.hpp replaces those parts).
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace foveal::render::detail {

/// Adds the placeholders to `root` (a checked glTF JSON); true when it changed anything.
/// A .glb's first buffer without a uri is its BIN chunk and stays as it is.
bool mend_for_tinygltf(nlohmann::json& root, bool binary);

/// `glb` (a .glb whose JSON chunk was already checked) with its JSON chunk replaced.
std::string glb_with_json(std::string_view glb, std::string_view json_chunk, const std::string& new_json);

}  // namespace foveal::render::detail

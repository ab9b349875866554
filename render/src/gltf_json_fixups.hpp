#pragma once
// Loads a .gltf/.glb into tinygltf (KTX2 images left undecoded), first mending what tinygltf 2.7 (built without Draco)
// refuses although the extensions allow it: index accessors of Draco primitives without
// a buffer view, and meshopt fallback buffers without data. The mended parts are never
// read: gltf_decode.hpp replaces them.
#include <string>

#include <tiny_gltf.h>

#include "foveal/core/error.hpp"

namespace foveal::render::detail {

/// tinygltf's load of `path`, with the fix-ups when the file uses either extension;
/// `warn` gets tinygltf's warnings.
Status load_tinygltf(tinygltf::Model& model, const std::string& path, std::string& warn);

}  // namespace foveal::render::detail

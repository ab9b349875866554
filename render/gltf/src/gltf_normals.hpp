#pragma once
// Normals and tangents a glTF mesh lacks, derived from its triangles.
#include <cstdint>
#include <vector>

#include "foveal/render/gltf_loader.hpp"

namespace foveal::render::detail {

/// Per-vertex normals from the triangles `idx` (a triangle list): each vertex sums its
/// triangles' area-weighted normals; one without a usable sum gets +z.
void generate_normals(std::vector<GltfVertex>& v, const std::vector<std::uint32_t>& idx);

/// Per-vertex tangents from the uv gradients (w: the bitangent's handedness), for
/// normal-mapped meshes without TANGENT; needs the normals.
void generate_tangents(std::vector<GltfVertex>& v, const std::vector<std::uint32_t>& idx);

}  // namespace foveal::render::detail

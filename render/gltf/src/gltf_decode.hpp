#pragma once
// Rewrites a loaded glTF model so the loader only meets plain accessors: meshopt-
// compressed buffer views, Draco-compressed primitives and sparse accessors are decoded
// into new buffers (docs/scenes.md). Every read is bounds-checked and every output
// counted against the loader's DecodeBudget before it is allocated; errors name the
// file and the object.
#include <cstddef>
#include <string>
#include <vector>

#include "gltf_internal.hpp"

namespace foveal::render::detail {

/// Runs the three steps below in the order they depend on each other.
Status decode_gltf_model(tinygltf::Model& m, const std::string& path, const GltfLimits& limits, DecodeBudget& budget);

/// EXT_meshopt_compression buffer views (gltf_meshopt.cpp).
Status decode_meshopt_views(tinygltf::Model& m, const std::string& path, DecodeBudget& budget);
/// KHR_draco_mesh_compression primitives (gltf_draco.cpp).
Status decode_draco_primitives(tinygltf::Model& m, const std::string& path, DecodeBudget& budget);
/// Sparse accessors that a primitive reads made dense (gltf_sparse.cpp); the others are
/// left alone. Without a buffer view at most limits.max_zero_accessor_count elements.
Status densify_sparse_accessors(tinygltf::Model& m, const std::string& path, const GltfLimits& limits, DecodeBudget& budget);

// Shared by the steps.

/// The most bytes one decoded view may take (before the budget: keeps sizes far from overflow).
inline constexpr std::size_t kMaxDecodedBytes = std::size_t{1} << 30;

/// `length` bytes at `offset` inside buffer view `view` (or inside buffer `buffer` when
/// view < 0), or an error naming `where`.
Result<const unsigned char*> buffer_span(const tinygltf::Model& m, int buffer, std::size_t offset, std::size_t length,
                                         const std::string& where);
Result<const unsigned char*> view_span(const tinygltf::Model& m, int view, std::size_t offset, std::size_t length,
                                       const std::string& where);

/// Appends `bytes` as a new buffer; returns its index.
int append_buffer(tinygltf::Model& m, std::vector<unsigned char> bytes);
/// Appends `bytes` as a new buffer with one view over all of it; returns the view index.
int append_buffer_view(tinygltf::Model& m, std::vector<unsigned char> bytes, std::size_t stride);

}  // namespace foveal::render::detail

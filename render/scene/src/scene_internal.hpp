#pragma once
// Shared by the scene loaders.
#include <string>
#include <vector>

#include "foveal/render/gltf_loader.hpp"
#include "foveal/render/scene.hpp"

namespace foveal::render::detail {

/// Uploads a triangle list into a Primitive with its vertex array set up.
Primitive upload_primitive(const std::vector<GltfVertex>& vertices, const std::vector<std::uint32_t>& indices, int material);

/// An RGBA8 texture with a full mip chain, trilinear and anisotropic filtering.
/// The concatenated vertex and index buffers and the draw records of `scene`
/// (SceneGeometry); its primitives' first_index and base_vertex already set.
void upload_geometry(Scene& scene, const std::vector<GltfVertex>& vertices, const std::vector<std::uint32_t>& indices);

/// Trilinear filtering with these wrap modes and no anisotropy (Scene::isotropic_samplers).
gl::Sampler isotropic_sampler(GLenum wrap_s, GLenum wrap_t);

gl::Texture upload_rgba8(const std::uint8_t* rgba, int width, int height, bool srgb, GLenum wrap_s, GLenum wrap_t,
                         std::size_t* bytes);

Result<Scene> load_gltf_scene(const std::string& path, const std::string& variant);
Result<Scene> make_pattern_scene(const std::string& spec);

}  // namespace foveal::render::detail

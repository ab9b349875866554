#pragma once
// glTF 2.0 (.gltf, .glb) to CPU-side triangles and RGBA8 images, validated against what
// the renderer relies on before anything is allocated from a count in the file: JSON
// depth and size, index references, accessor ranges (64-bit, overflow-checked), types,
// node transforms, image dimensions (docs/bad-input.md, "Crafted data"). Messages name
// the file and the JSON path ("meshes[0].primitives[1].material"). No GL here: the
// compositor uploads through a GltfSink (gltf_scene.cpp); the fuzz target calls it too.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "foveal/core/error.hpp"
#include "foveal/render/scene_types.hpp"

namespace foveal::render {

struct GltfLimits {
  std::size_t max_file_bytes = std::size_t{1} << 30;   ///< the .gltf/.glb and each file it references
  std::size_t max_json_bytes = std::size_t{64} << 20;  ///< the JSON (.gltf, or a .glb's JSON chunk)
  int max_texture_size = 16384;  ///< widest image side; the compositor passes GL_MAX_TEXTURE_SIZE
  std::size_t max_image_bytes = std::size_t{256} << 20;    ///< one image decoded to RGBA8
  std::size_t max_decoded_bytes = std::size_t{4} << 30;    ///< all images and vertex/index data together
  std::size_t max_zero_accessor_count = std::size_t{1} << 20;  ///< elements of an accessor without a buffer view
  bool external_files = true;  ///< false: only data: URIs and the .glb's own chunk (fuzzing)
};

struct GltfVertex {
  float position[3];
  float normal[3];
  float uv[2];
  float tangent[4];
  float uv1[2];    ///< TEXCOORD_1 (TEXCOORD_0 when absent)
  float color[4];  ///< COLOR_0, white when absent
};

/// One image in one colour space, ready to upload: width × height RGBA8.
struct GltfTexture {
  const std::uint8_t* rgba = nullptr;
  int width = 0, height = 0;
  bool srgb = false;
  int wrap_s = 10497, wrap_t = 10497;  ///< glTF sampler codes (REPEAT unless the sampler says otherwise)
};

/// Where the loader puts textures and triangle lists; each call returns the index the
/// item has in the caller's scene (Material texture indices and DrawItem::primitive).
class GltfSink {
 public:
  virtual ~GltfSink() = default;
  virtual int add_texture(const GltfTexture& t) = 0;
  virtual int add_primitive(const std::vector<GltfVertex>& vertices, const std::vector<std::uint32_t>& indices,
                            int material) = 0;
};

struct GltfScene {
  std::vector<Material> materials;
  std::vector<DrawItem> draws;
  Bounds bounds;
  ViewPose view;  ///< the file's first camera, else source "framing"
  std::size_t triangles = 0;
  std::vector<PunctualLight> lights;  ///< KHR_lights_punctual, one per node that has one
  std::vector<MaterialVariant> variants;  ///< KHR_materials_variants, in the file's order
  std::vector<std::string> warnings;  ///< what the file uses that is ignored, once each ("FILE: ...")
};

/// Loads a .gltf or .glb file (told apart by the "glTF" magic).
Result<GltfScene> load_gltf(const std::string& path, const GltfLimits& limits, GltfSink& sink);

/// The same from bytes in memory: `name` is used in messages, external files are
/// looked up under `base_dir` (when limits.external_files).
Result<GltfScene> load_gltf_bytes(std::string_view bytes, const std::string& name, const std::string& base_dir,
                                  const GltfLimits& limits, GltfSink& sink);

}  // namespace foveal::render

#pragma once
// Loading a glTF written by a test, without GL: the loader's output (draws, lights,
// warnings, errors), the meshes and images counted and dropped.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/render/gltf_loader.hpp"

namespace foveal::test {

/// A sink that uploads nothing: it counts textures and primitives and gives them ids.
class NullGltfSink : public render::GltfSink {
 public:
  int add_texture(const render::GltfTexture&) override { return textures++; }
  int add_primitive(const std::vector<render::GltfVertex>&, const std::vector<std::uint32_t>&, int) override { return primitives++; }
  int textures = 0, primitives = 0;
};

/// Loads `j` as a .gltf named `name` in messages (external files under ".").
inline Result<render::GltfScene> load_gltf_json(const nlohmann::json& j, const std::string& name) {
  NullGltfSink sink;
  return render::load_gltf_bytes(j.dump(), name, ".", {}, sink);
}

}  // namespace foveal::test

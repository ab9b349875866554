// The compositor's side of glTF loading: the CPU loader (gltf_loader.cpp) checks and
// decodes, this uploads its textures and triangle lists, within this context's
// GL_MAX_TEXTURE_SIZE.
#include <algorithm>

#include "foveal/render/gltf_loader.hpp"
#include "foveal/render/light_rig.hpp"
#include "scene_internal.hpp"

namespace foveal::render::detail {

namespace {

GLenum wrap_mode(int gltf) {
  switch (gltf) {
    case 33071: return GL_CLAMP_TO_EDGE;
    case 33648: return GL_MIRRORED_REPEAT;
    default: return GL_REPEAT;
  }
}

class UploadSink : public GltfSink {
 public:
  explicit UploadSink(Scene& s) : s_(s) {}

  int add_texture(const GltfTexture& t) override {
    s_.textures.push_back(upload_rgba8(t.rgba, t.width, t.height, t.srgb, wrap_mode(t.wrap_s), wrap_mode(t.wrap_t),
                                       &s_.texture_bytes));
    s_.isotropic_samplers.push_back(isotropic_sampler(wrap_mode(t.wrap_s), wrap_mode(t.wrap_t)));
    return static_cast<int>(s_.textures.size()) - 1;
  }

  int add_primitive(const std::vector<GltfVertex>& v, const std::vector<std::uint32_t>& idx, int material) override {
    Primitive p = upload_primitive(v, idx, material);
    p.first_index = static_cast<std::uint32_t>(all_indices.size());
    p.base_vertex = static_cast<std::uint32_t>(all_vertices.size());
    for (std::size_t i = 0; i < v.size(); ++i) {
      const glm::vec3 q(v[i].position[0], v[i].position[1], v[i].position[2]);
      p.local_bounds.min = i ? glm::min(p.local_bounds.min, q) : q;
      p.local_bounds.max = i ? glm::max(p.local_bounds.max, q) : q;
    }
    all_vertices.insert(all_vertices.end(), v.begin(), v.end());
    all_indices.insert(all_indices.end(), idx.begin(), idx.end());
    s_.primitives.push_back(std::move(p));
    return static_cast<int>(s_.primitives.size()) - 1;
  }

  // Every primitive's data, concatenated for SceneGeometry.
  std::vector<GltfVertex> all_vertices;
  std::vector<std::uint32_t> all_indices;

 private:
  Scene& s_;
};

}  // namespace

namespace {

// KHR_materials_variants: the primitives' materials under variant `name`.
Status select_variant(Scene& scene, const std::vector<MaterialVariant>& variants, const std::string& path, const std::string& name) {
  for (const MaterialVariant& v : variants) scene.variants.push_back(v.name);
  if (name.empty()) return {};
  std::string names;
  for (const MaterialVariant& v : variants) {
    if (v.name == name) {
      for (const auto& [primitive, material] : v.primitive_material)
        scene.primitives[static_cast<std::size_t>(primitive)].material = material;
      scene.variant = name;
      return {};
    }
    names += (names.empty() ? "" : ", ") + v.name;
  }
  return bad_input(path + ": no material variant '" + name + "' (" +
                   (variants.empty() ? std::string("the file has no KHR_materials_variants") : "the file's variants: " + names) + ")");
}

// What the drawn materials use beyond metal-roughness (MaterialFeature bits).
unsigned drawn_features(const Scene& scene) {
  unsigned f = 0;
  for (const DrawItem& d : scene.draws) {
    const int m = scene.primitives[static_cast<std::size_t>(d.primitive)].material;
    if (m >= 0) f |= scene.materials[static_cast<std::size_t>(m)].features;
  }
  return f;
}

}  // namespace

Result<Scene> load_gltf_scene(const std::string& path, const std::string& variant) {
  GltfLimits limits;
  GLint max_texture = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture);
  if (max_texture > 0) limits.max_texture_size = std::min(limits.max_texture_size, static_cast<int>(max_texture));
  Scene scene;
  scene.name = path;
  UploadSink sink(scene);
  auto loaded = load_gltf(path, limits, sink);
  if (!loaded) return loaded.error();
  scene.materials = std::move(loaded->materials);
  scene.draws = std::move(loaded->draws);
  scene.bounds = loaded->bounds;
  scene.view = std::move(loaded->view);
  scene.triangles = loaded->triangles;
  scene.warnings = std::move(loaded->warnings);
  scene.lights = std::move(loaded->lights);
  if (scene.lights.size() > static_cast<std::size_t>(kMaxFileLights)) {
    scene.warnings.push_back(path + ": " + std::to_string(scene.lights.size()) + " KHR_lights_punctual light nodes; the first " +
                             std::to_string(kMaxFileLights) + " are used");
    scene.lights.resize(static_cast<std::size_t>(kMaxFileLights));
  }
  if (Status st = select_variant(scene, loaded->variants, path, variant); !st) return st.error();
  scene.features = drawn_features(scene);
  upload_geometry(scene, sink.all_vertices, sink.all_indices);
  return scene;
}

}  // namespace foveal::render::detail

#pragma once
// What the compositor draws: GPU meshes and materials from a glTF 2.0 file, or one of
// the built-in screen-space patterns (`pattern:NAME`). Loading needs a current GL
// context; a Scene must be destroyed while it is current. Not thread-safe.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "foveal/core/error.hpp"
#include "foveal/render/gl_objects.hpp"

namespace foveal::render {

struct Bounds {
  glm::vec3 min{0.0f}, max{0.0f};
  glm::vec3 center() const { return (min + max) * 0.5f; }
  float radius() const;  ///< half the diagonal
};

/// Which texture coordinates a material texture reads, and how they are transformed
/// (KHR_texture_transform: uv' = matrix * (uv, 1)).
struct TextureUv {
  glm::mat3 matrix{1.0f};
  int set = 0;  ///< 0: TEXCOORD_0, 1: TEXCOORD_1
};

/// glTF 2.0 metal-roughness material. Texture indices point into Scene::textures (-1: none).
/// A KHR_materials_pbrSpecularGlossiness material keeps its diffuse factor and texture in
/// base_color, its specular-glossiness texture in metal_rough_tex, and is converted to
/// metal-roughness per fragment (docs/scenes.md).
struct Material {
  enum Slot { base_color_slot, metal_rough_slot, normal_slot, occlusion_slot, emissive_slot, slot_count };
  glm::vec4 base_color{1.0f};
  float metallic = 1.0f, roughness = 1.0f;
  glm::vec3 emissive{0.0f};
  float normal_scale = 1.0f, occlusion_strength = 1.0f;
  float alpha_cutoff = -1.0f;  ///< >= 0 for alphaMode MASK
  bool unlit = false;          ///< KHR_materials_unlit
  bool double_sided = false;
  int base_color_tex = -1, metal_rough_tex = -1, normal_tex = -1, occlusion_tex = -1, emissive_tex = -1;
  std::array<TextureUv, slot_count> uv{};  ///< per texture, indexed by Slot
  bool spec_gloss = false;                 ///< KHR_materials_pbrSpecularGlossiness
  glm::vec3 specular{1.0f};                ///< its specularFactor
  float glossiness = 1.0f;                 ///< its glossinessFactor
};

/// One indexed triangle list with interleaved vertices (position, normal, uv, tangent,
/// second uv, colour).
struct Primitive {
  gl::VertexArray vao;
  gl::Buffer vertices, indices;
  int index_count = 0;
  int material = -1;
};

struct DrawItem {
  int primitive = 0;
  glm::mat4 world{1.0f};
};

/// Built-in test patterns, drawn in each eye's screen space (the camera plays no part).
struct Pattern {
  enum class Kind { checker, stripes_h, stripes_v, noise } kind = Kind::checker;
  float angle_deg = 0.0f;  ///< rotation of the pattern about the viewport centre
  float tile_px = 32.0f;   ///< screen pixels per texture repeat at angle 0
  gl::Texture texture;     ///< one tile, mipmapped, repeating
};

/// Where the viewer's head is: the midpoint between the eyes, looking along -z.
struct ViewPose {
  glm::mat4 head_to_world{1.0f};  ///< rotation and translation only
  float units_per_meter = 1.0f;   ///< scales the IPD into scene units
  std::string source;             ///< "view file", "glTF camera NAME" or "framing"
};

struct Scene {
  std::string name;  ///< file name or pattern spec
  std::vector<gl::Texture> textures;
  std::vector<Material> materials;
  std::vector<Primitive> primitives;
  std::vector<DrawItem> draws;
  Bounds bounds;
  ViewPose view;
  std::size_t triangles = 0;
  std::size_t texture_bytes = 0;  ///< GPU memory of the textures, mip levels included
  std::optional<Pattern> pattern;
  std::vector<std::string> warnings;  ///< what the file uses that is ignored, once each

  bool is_pattern() const { return pattern.has_value(); }
};

/// Loads `spec`: "pattern:NAME[@ANGLE]" (docs/scenes.md) or a .gltf / .glb path.
/// A view file "<file without extension>.view.json" next to the glTF sets the head pose
/// (docs/scenes.md); else the file's first camera; else a framing camera.
/// Errors name the file: malformed glTF, a missing or undecodable image, an unsupported
/// required extension, unsupported primitive modes or accessors.
Result<Scene> load_scene(const std::string& spec);

/// The names load_scene accepts after "pattern:".
const std::vector<std::string>& pattern_names();

}  // namespace foveal::render

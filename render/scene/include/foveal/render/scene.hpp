#pragma once
// What the compositor draws: GPU meshes and materials from a glTF 2.0 file, or one of
// the built-in screen-space patterns (`pattern:NAME`). Loading needs a current GL
// context; a Scene must be destroyed while it is current. Not thread-safe.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "foveal/core/error.hpp"
#include "foveal/render/gl_objects.hpp"
#include "foveal/render/scene_types.hpp"

namespace foveal::render {

/// One indexed triangle list with interleaved vertices (position, normal, uv, tangent,
/// second uv, colour: GltfVertex).
struct Primitive {
  gl::VertexArray vao;
  gl::Buffer vertices, indices;
  int index_count = 0;
  int material = -1;
  /// Where its indices and vertices start in SceneGeometry's buffers.
  std::uint32_t first_index = 0, base_vertex = 0;
  Bounds local_bounds;  ///< of its vertex positions, in its own space
};

/// Every primitive's vertices (GltfVertex, interleaved) and indices concatenated into
/// buffers, and one record per DrawItem (DrawRecord): what the visibility pipeline's
/// material pass fetches a triangle from (shaders/common/visibility_geometry.glsl),
/// through texture-buffer views of them (llvmpipe reads a shader storage buffer one
/// scalar per lane at a time, a texel fetch as one gather per texel).
struct SceneGeometry {
  gl::Buffer vertices, indices, draws;
  gl::Texture vertex_pairs;  ///< vertices as RG32F: 9 texels per GltfVertex
  gl::Texture triangles;     ///< indices as RGB32UI: one texel per triangle
  gl::Texture draw_floats;   ///< draws as RGBA32F: 8 texels per DrawRecord
  gl::Texture draw_uints;    ///< draws as RGBA32UI: texel 7 of each is first_index, base_vertex, material
};

/// One DrawItem as the shaders read it (std430; the layout of visibility_geometry.glsl).
struct DrawRecord {
  glm::mat4 model{1.0f};
  glm::vec4 normal_matrix[3]{};  ///< columns of transpose(inverse(mat3(model)))
  std::uint32_t first_index = 0, base_vertex = 0;
  std::uint32_t material = 0;  ///< index into Scene::materials; materials.size(): the default
  std::uint32_t pad = 0;
};
static_assert(sizeof(DrawRecord) == 128, "std430 layout of DrawRecord");

/// Built-in test patterns, drawn in each eye's screen space (the camera plays no part).
struct Pattern {
  enum class Kind { checker, stripes_h, stripes_v, noise } kind = Kind::checker;
  float angle_deg = 0.0f;  ///< rotation of the pattern about the viewport centre
  float tile_px = 32.0f;   ///< screen pixels per texture repeat at angle 0
  gl::Texture texture;     ///< one tile, mipmapped, repeating
};

struct Scene {
  std::string name;  ///< file name or pattern spec
  std::vector<gl::Texture> textures;
  /// Per texture: its wrap modes and trilinear filtering without anisotropy, for the
  /// visibility pipeline's material pass, which chooses texture levels itself (the
  /// textures' own 8× anisotropy would take the full-screen pass's implicit derivatives).
  std::vector<gl::Sampler> isotropic_samplers;
  std::vector<Material> materials;
  std::vector<Primitive> primitives;
  std::vector<DrawItem> draws;
  SceneGeometry geometry;  ///< glTF scenes; empty for patterns
  Bounds bounds;
  ViewPose view;
  std::size_t triangles = 0;
  std::size_t texture_bytes = 0;  ///< GPU memory of the textures, mip levels included
  std::optional<Pattern> pattern;
  /// KHR_lights_punctual lights (at most kMaxFileLights, light_rig.hpp); empty: the rig lights it.
  std::vector<PunctualLight> lights;
  std::vector<std::string> warnings;  ///< what the file uses that is ignored, once each
  /// KHR_materials_variants: the file's variants and the one drawn ("": the default materials).
  std::vector<std::string> variants;
  std::string variant;
  /// MaterialFeature bits of the drawn materials: the compositor's shader variant and
  /// G-buffer layout for the scene (docs/scenes.md, "Materials").
  unsigned features = 0;

  bool is_pattern() const { return pattern.has_value(); }
};

/// Loads `spec`: "pattern:NAME[@ANGLE]" (docs/scenes.md) or a .gltf / .glb path.
/// A view file "<file without extension>.view.json" next to the glTF sets the head pose
/// (docs/scenes.md); else the file's first camera; else a framing camera.
/// Errors name the file: malformed glTF, a missing or undecodable image, an unsupported
/// required extension, unsupported primitive modes or accessors.
struct SceneOptions {
  std::string variant;  ///< KHR_materials_variants variant to draw; "": the default materials
};

/// Loads `spec` with `options`: a glTF path, `pattern:NAME`, or `bundled:NAME` (the
/// scene shipped in data/scenes/NAME, found wherever foveal's data is: works outside the
/// repository). An unknown variant (or one asked of a pattern) is bad_input naming the
/// file's variants; an unknown bundled name names the bundled ones.
Result<Scene> load_scene(const std::string& spec, const SceneOptions& options = {});

/// Moves the viewer along its line of sight to 1.05 bounding radii from the scene's
/// centre, so that an object scene fills the view (the benchmarks' "filled" framing; an
/// object seen from its framing distance covers a fraction of the frame).
void fill_view(Scene& scene);

/// The bundled scenes' names (the folders of data/scenes), for `bundled:NAME`.
std::vector<std::string> bundled_scene_names();
/// The glTF file of bundled scene `name`; bad_input naming the bundled ones otherwise.
Result<std::string> bundled_scene_path(const std::string& name);

/// The names load_scene accepts after "pattern:".
const std::vector<std::string>& pattern_names();

}  // namespace foveal::render

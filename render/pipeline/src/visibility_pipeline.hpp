#pragma once
// The visibility pipeline's own passes (docs/rmfr.md, "Pipelines"): the full-resolution
// visibility pass (depth + draw and triangle per pixel) and the material pass, which
// evaluates the glTF material only at the samples the eye's mapping keeps and writes the
// G-buffer layout the lighting pass reads. The compositor runs lighting and resolve as
// for the G-buffer pipeline.
#include <array>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "foveal/core/error.hpp"
#include "foveal/image/foveation_plan.hpp"
#include "foveal/render/gl_objects.hpp"
#include "foveal/render/shader_loader.hpp"
#include "render_targets.hpp"

namespace foveal::render {
struct Scene;
struct EyeView;
}  // namespace foveal::render

namespace foveal::render::detail {

class VisibilityPipeline {
 public:
  /// Compiles its programs. Targets are made on first use.
  static Result<VisibilityPipeline> create(const gl::ShaderLoader& shaders, int eye_width, int eye_height);

  /// Recompiles the material pass for `layout` (the scene's material features) and drops
  /// the surfaces, which are remade in it on next use. Errors: the shaders' (compile).
  Status use_layout(const gl::ShaderLoader& shaders, const SurfaceLayout& layout);
  const SurfaceLayout& layout() const { return layout_; }

  /// Builds the programs of mapping variant `mapping` if its kernel is not built up front
  /// (MethodKernel::built_up_front: those are built by create and use_layout) and they
  /// are not built yet.
  Status ensure_mapping(const gl::ShaderLoader& shaders, std::size_t mapping);

  /// The grid jitter (texels; shaders/temporal/jitter.glsl) of mapping variant `mapping`'s
  /// classification and material programs: 0 unless temporal accumulation is on.
  void set_jitter(std::size_t mapping, glm::vec2 jitter);

  /// Depth and (draw + 1, triangle) of every pixel of one eye. Nothing for patterns.
  void visibility_pass(const Scene& scene, const EyeView& view);

  /// Fills `dst` over `regions` (viewport rectangles x, y, w, h; one per layer of a
  /// layered plan) with the G-buffer of the samples `plan` keeps, through the
  /// kernel's variant `mapping` (mapping_index). The mapping uniforms are set here.
  void material_pass(const Scene& scene, const EyeView& view, const EyePlan& plan, std::size_t mapping,
                     const std::vector<glm::ivec4>& regions, MaterialSurface& dst);

  /// The W×H surface of the full method, shared by both eyes.
  MaterialSurface& full_surface();
  /// Eye `eye`'s surface: exactly w×h, or at least w×h when `grow_only` (layered atlases).
  MaterialSurface& eye_surface(std::size_t eye, int w, int h, bool grow_only);

  /// The last visibility pass's depth (D32F, W×H): the opaque depth the blend pass tests.
  GLuint depth_texture() const { return visibility_ ? visibility_->depth.id() : 0; }

  /// Bytes of the id/depth target, of the eyes' surfaces, of the full surface.
  std::size_t visibility_bytes() const { return visibility_ ? visibility_->bytes() : 0; }
  std::size_t eye_surface_bytes() const;
  std::size_t full_surface_bytes() const { return full_ ? full_->bytes() : 0; }

 private:
  int eye_w_ = 0, eye_h_ = 0;
  SurfaceLayout layout_;
  gl::Program visibility_prog_, visibility_mask_prog_, tiles_prog_;
  std::vector<gl::Program> classify_progs_, material_progs_, pattern_progs_;  // per kernel variant (mapping_index)
  gl::VertexArray empty_vao_;
  std::optional<VisibilityTarget> visibility_;
  std::array<std::optional<MaterialSurface>, 2> eyes_;
  std::optional<MaterialSurface> full_;
};

}  // namespace foveal::render::detail

#pragma once
// Transparency at the kept samples (FrameParams::blend_at == BlendAt::samples; docs/rmfr.md,
// "Transparency at the kept samples"): the forward draws depth-peeled at W×H into layers
// of ids (cheap: no shading), then each layer, deepest first, shaded per material at the
// eye's kept samples and composited "over" its lit reduced buffer, so that the inverse
// pass takes the blended result to the output and no full-resolution blend pass runs.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
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

class TransparentLayers {
 public:
  /// Layers peeled at most. A pixel with more blended surfaces than this keeps its
  /// nearest kMaxLayers; the deeper ones are not drawn, and such pixels are counted.
  static constexpr int kMaxLayers = 4;

  /// Builds the peel program and mapping variant `variant`'s composite program for the
  /// lighting defines `lit_defines` (the lighting pass's: features and lights); a change
  /// of defines drops the composite programs built so far.
  Status ensure_programs(const gl::ShaderLoader& shaders, std::size_t variant, const std::string& lit_defines);

  /// Peels the scene's forward draws (W×H, the eye's `view`) in front of `opaque_depth`
  /// until a layer is empty or kMaxLayers are taken; returns how many are not empty, and
  /// adds to `dropped` the pixels that had surfaces beyond the cap.
  int peel(const Scene& scene, const glm::mat4& view_proj, GLuint opaque_depth, int width, int height, std::size_t& dropped);

  /// Composites the first `layers` layers, deepest first, over `regions` of `target`
  /// (the eye's lit reduced buffer; the mapping sees `texture_size` texels) through the
  /// plan's mapping variant `variant`. The caller binds the lights (unit 5 shadow, 7
  /// light tiles, 11 sheen table, uniform block 0) and enables the blend.
  void composite(const Scene& scene, const EyeView& view, const EyePlan& plan, std::size_t variant,
                 const std::vector<glm::ivec4>& regions, glm::vec2 texture_size, glm::ivec4 light_grid, int layers,
                 const ColorTarget& target, std::size_t eye);

  /// The texels eye `eye`'s last composite shaded, all layers (GL_SAMPLES_PASSED of the
  /// classifications: one per shaded texel); waits for them. Forgets them.
  std::size_t take_shaded(std::size_t eye);

  /// Bytes of the layer targets made so far.
  std::size_t bytes() const;

 private:
  gl::Program peel_prog_;
  std::vector<gl::Program> composite_progs_, classify_progs_;  // per mapping variant (mapping_index)
  std::string lit_defines_;
  gl::VertexArray empty_vao_;
  // Layer k's ids and depth (W×H); one more counts the pixels beyond the cap.
  std::array<std::optional<VisibilityTarget>, kMaxLayers + 1> layers_;
  gl::Query any_, count_;
  // The composite's framebuffer: the eye's reduced buffer and a depth of the same size or
  // larger, which holds each texel's material for the EQUAL test.
  gl::Framebuffer fbo_;
  gl::Texture depth_;
  int depth_w_ = 0, depth_h_ = 0;
  std::array<std::array<gl::Query, kMaxLayers>, 2> shaded_;  // per eye and layer
  std::array<int, 2> shaded_layers_{};
};

}  // namespace foveal::render::detail

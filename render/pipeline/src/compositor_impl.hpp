#pragma once
// The compositor's private state (Compositor::Impl): its programs, targets and timer, and
// the members each pass runs. Only the compositor's own files include it; each member
// is defined in the file named beside its group.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "foveal/render/compositor.hpp"
#include "foveal/render/gl_objects.hpp"
#include "foveal/render/shader_loader.hpp"
#include "foveal/render/stereo_camera.hpp"
#include "foveal/rmfr.hpp"
#include "pass_timer.hpp"
#include "pass_uniforms.hpp"
#include "render_targets.hpp"
#include "temporal_accumulation.hpp"
#include "transparent_layers.hpp"
#include "visibility_pipeline.hpp"

namespace foveal::render {

// An RMFR eye's plan as foveal-rmfr takes it, and the display's lens (method_binding.cpp).
rmfr::Plan rmfr_plan(const EyePlan& p);
rmfr::Lens rmfr_lens(const LensDistortion& l);

struct Compositor::Impl {
  CompositorOptions opt;
  int eye_w = 0, eye_h = 0;
  gl::Program gbuffer_prog, pattern_prog, shadow_prog, blend_prog;
  // One per method kernel (mapping_index: RMFR's, KFR's, the layers', the inset's; a
  // kernel not built up front is built on first use); resolve also with and without the
  // lens. RMFR maps and resolves through foveal-rmfr, so its map and resolve slots stay empty.
  std::vector<gl::Program> map_progs = std::vector<gl::Program>(mapping_variant_count());
  std::vector<gl::Program> lighting_progs = std::vector<gl::Program>(mapping_variant_count());
  std::vector<std::array<gl::Program, 2>> resolve_progs = std::vector<std::array<gl::Program, 2>>(mapping_variant_count());
  std::string lit_defines;  // the lighting programs' defines for the scene's features and lights
  std::optional<rmfr::Foveator> foveator;  // RMFR's mapping and resolve passes
  gl::VertexArray empty_vao;
  gl::Buffer lights_ubo;
  // The eye's per-tile lists of the file's lights (light_tiles.hpp) and the grid the
  // lighting and blend passes read them by (w 0: no lists).
  gl::Buffer light_tiles_buffer;
  gl::Texture light_tiles_texture;
  glm::ivec4 light_grid{0};
  // The programs and targets that depend on the scene's material features (its shader
  // variant, docs/scenes.md "Materials"): remade when a scene with other features comes.
  gl::ShaderLoader shaders;
  detail::SurfaceLayout layout;     // what the scene's features got (at most SurfaceLayout::kMaxTargets)
  unsigned requested_features = 0;  // the scene's
  bool requested_file_lights = false;  // whether the lighting programs loop over the file's lights
  gl::Texture sheen_albedo;  // sheen_albedo.hpp, made for the first scene with sheen
  std::optional<detail::ColorTarget> behind;  // the eye's opaque result under transmission (first use)
  std::optional<detail::SurfaceTargets> gbuffer;  // made by the first G-buffer-pipeline frame
  std::array<std::optional<detail::SurfaceTargets>, 2> transformed;
  std::optional<detail::VisibilityPipeline> visibility;
  std::array<std::optional<detail::ColorTarget>, 2> reduced;
  std::optional<detail::ColorTarget> undistorted;  // blend target under the lens (made on first use)
  std::optional<detail::TemporalAccumulation> temporal;  // FrameParams::temporal's pass and histories (first use)
  std::optional<detail::TransparentLayers> transparent;  // BlendAt::samples's layers and programs (first use)
  // Per eye: the blended fragments composited this frame (PassTimes::blend_samples).
  std::array<gl::Query, 2> blend_counts;
  std::array<bool, 2> blend_counted{};
  detail::ColorTarget output, shadow;
  std::array<EyePlan, 2> plans{};
  detail::PassTimer timer;

  GLenum reduced_format() const { return opt.float_output ? GL_RGBA32F : GL_SRGB8_ALPHA8; }

  // The depth texture of the eye just drawn: the G-buffer's or the visibility target's.
  GLuint opaque_depth(Pipeline pipeline) const {
    return pipeline == Pipeline::visibility ? visibility->depth_texture() : gbuffer->depth.id();
  }

  // The passes (compositor_passes.cpp).
  void draw_geometry(const Scene& scene, const EyeView& v);
  void draw_pattern(const Scene& scene);
  void shadow_pass(const Scene& scene);
  Status full_resolution_pass(const Scene& scene, const EyeView& view, Pipeline pipeline);
  Result<const detail::SurfaceTargets*> gbuffer_surface(const EyePlan& plan, std::size_t eye, std::size_t variant,
                                                       const std::vector<glm::ivec4>& regions);
  const detail::SurfaceTargets* visibility_surface(const Scene& scene, const EyeView& view, const EyePlan& plan,
                                                   std::size_t eye, std::size_t variant,
                                                   const std::vector<glm::ivec4>& regions);
  void run_latch(const FoveaLatch& latch, std::array<EyeFoveation, 2>& eyes, PassTimes& times);
  void lighting_pass(GLuint p, const detail::SurfaceTargets& src, glm::ivec2 origin, const EyeView& v);
  Status resolve_pass(const EyePlan& plan, std::size_t variant, const detail::ColorTarget& lit, glm::vec2 texture_size, GLuint fbo,
                      glm::ivec2 origin, const LensDistortion* lens);
  Status resolve_full(const EyePlan& plan, GLuint texture, GLuint fbo, glm::ivec2 origin, const LensDistortion* lens);
  void copy_behind(GLuint color, glm::ivec2 origin);
  void blend_pass(const Scene& scene, const EyeView& v, GLuint fbo, GLuint color, glm::ivec2 origin, GLuint depth);

  // Blended surfaces at the eye's kept samples, into its lit reduced buffer `target`
  // (BlendAt::samples; transparent_layers.cpp): the layers composited. And the count of
  // the eye's blend-pass fragments, begun (ended by the caller's glEndQuery).
  Result<int> samples_blend(const Scene& scene, const EyeView& view, const EyePlan& plan, std::size_t eye, std::size_t variant,
                            const std::vector<glm::ivec4>& regions, glm::vec2 texture_size, const detail::ColorTarget& target,
                            PassTimes& times);
  void begin_blend_count(std::size_t eye);

  // Temporal accumulation (temporal_accumulation.cpp): this frame's grid jitter on the
  // eye's RMFR programs (0 unless `on`; off drops the eye's history), and the eye's lit
  // reduced buffer accumulated and resolved into `fbo` at `origin`, through `lens` if given.
  Status use_jitter(std::size_t eye, std::size_t variant, bool on);
  Status temporal_resolve(std::size_t eye, const EyePlan& plan, const detail::ColorTarget& lit,
                          const detail::SurfaceTargets& surface, const Scene& scene, const EyeView& view, GLuint fbo,
                          glm::ivec2 origin, const LensDistortion* lens);

  // The programs: shader variants for the scene's features and lights, the described
  // methods' on first use (compositor_programs.cpp).
  Status build(gl::Program& out, const std::vector<gl::ShaderStage>& stages, const std::string& defines,
               const std::vector<gl::VirtualFile>& files = {}) const;
  Status use_features(unsigned features, bool file_lights);
  Status ensure_variant(std::size_t v);

  // The render targets, made or grown on first use (compositor_targets.cpp).
  void ensure_transformed(std::size_t eye, int w, int h, bool grow_only);
  void ensure_undistorted();
  void ensure_behind();
  void ensure_reduced(std::size_t eye, int w, int h, bool grow_only);
  Result<const detail::SurfaceTargets*> gbuffer_targets();
};

}  // namespace foveal::render

// The compositor's frame: create() builds the programs and targets every frame needs,
// render() runs the passes in order for both eyes (the passes themselves:
// compositor_passes.cpp), and the output and state are read back.
#include "foveal/render/compositor.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>

#include "compositor_impl.hpp"
#include "foveal/render/light_rig.hpp"
#include "foveal/render/light_tiles.hpp"
#include "foveal/render/scene.hpp"
#include "foveal/render/stereo_camera.hpp"
#include "foveal/rmfr.hpp"

namespace foveal::render {

namespace {

using Clock = std::chrono::steady_clock;

using detail::Pass;
using detail::set;

struct Camera {
  Pose head;
  double ipd_mm = 0;
};

// The frame's head pose and IPD, checked; the orientation renormalised (a pose that went
// through float arithmetic is a little off unit length).
Result<Camera> frame_camera(const FrameParams& p, const DisplayModel& model) {
  Camera c{p.head, p.ipd_mm == 0.0 ? double{model.ipd_mm} : p.ipd_mm};
  if (!std::isfinite(c.ipd_mm) || !(c.ipd_mm > 0.0) || c.ipd_mm > 200.0)
    return bad_input("frame: ipd_mm " + std::to_string(p.ipd_mm) + " is not in (0, 200] mm");
  if (!is_finite(c.head) || !(glm::length(c.head.orientation) > 1e-6f))
    return bad_input("frame: the head pose is not finite or its orientation is zero");
  c.head.orientation = renormalized(c.head.orientation);
  return c;
}

}  // namespace

Result<Compositor> Compositor::create(const CompositorOptions& o, const gl::ShaderLoader& shaders) {
  if (o.width < 2 || o.height < 1 || o.width % 2 != 0 || o.width > 16384 || o.height > 16384)
    return bad_input("output size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                     ": expected an even width and both in [1, 16384]");
  auto impl = std::make_unique<Impl>();
  impl->opt = o;
  impl->eye_w = o.width / 2;
  impl->eye_h = o.height;
  impl->shaders = shaders;
  const std::vector<std::pair<gl::Program*, std::vector<gl::ShaderStage>>> programs = {
      {&impl->pattern_prog, {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "pattern.frag"}}},
      {&impl->shadow_prog, {{GL_VERTEX_SHADER, "shadow.vert"}}},
  };
  for (const auto& [prog, stages] : programs)
    if (Status s = impl->build(*prog, stages, {}); !s) return s.error();
  for (std::size_t v = 0; v < mapping_variant_count(); ++v) {  // RMFR's resolve is foveal-rmfr's
    if (!mapping_kernel(v).built_up_front || mapping_kernel(v).rmfr_passes) continue;
    for (std::size_t lens = 0; lens < 2; ++lens)
      if (Status s = impl->build(impl->resolve_progs[v][lens], {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "resolve.frag"}},
                                 lens ? "#define DISTORTION 1\n" : "", mapping_files(v));
          !s)
        return s.error();
  }

  auto foveator = rmfr::Foveator::create();
  if (!foveator) return foveator.error();
  impl->foveator = std::move(*foveator);
  impl->empty_vao = gl::VertexArray::create();
  impl->lights_ubo = gl::Buffer::create();
  glNamedBufferStorage(impl->lights_ubo.id(), sizeof(LightBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
  impl->light_tiles_buffer = gl::Buffer::create();
  {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &id);
    impl->light_tiles_texture = gl::Texture(id);
  }
  auto visibility = detail::VisibilityPipeline::create(shaders, impl->eye_w, impl->eye_h);
  if (!visibility) return visibility.error();
  impl->visibility.emplace(std::move(*visibility));
  if (Status s = impl->use_features(0, false); !s) return s.error();  // a plain, rig-lit scene's variant
  impl->output = detail::ColorTarget::create(o.width, o.height, o.float_output ? GL_RGBA32F : GL_SRGB8_ALPHA8, false);
  impl->shadow = detail::ColorTarget::create_shadow(o.shadow_map_size);
  if (glCheckNamedFramebufferStatus(impl->output.fbo.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    return Error{ErrorKind::unsupported, "the output framebuffer is incomplete on this GL implementation"};
  return Compositor(std::move(impl));
}

Compositor::Compositor(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Compositor::Compositor(Compositor&&) noexcept = default;
Compositor& Compositor::operator=(Compositor&&) noexcept = default;
Compositor::~Compositor() = default;

Result<PassTimes> Compositor::render(const Scene& scene, const FrameParams& params, const FoveaLatch& latch) {
  Impl& m = *impl_;
  const auto camera = frame_camera(params, m.opt.model);
  if (!camera) return camera.error();
  if (Status s = m.use_features(scene.features, !scene.lights.empty()); !s) return s.error();
  const auto cpu_start = Clock::now();
  PassTimes times;
  times.pipeline = params.pipeline;
  times.start_ns = monotonic_now_ns();
  m.timer.begin_frame();
  m.timer.mark(Pass::shadow);

  // The file's own lights when it has any (no shadow map: only the rig's sun casts one).
  const bool file_lights = !scene.lights.empty();
  LightBlock lights = file_lights ? make_scene_lights(scene.lights) : make_light_rig(scene.bounds, m.opt.point_lights);
  if (!scene.is_pattern() && !file_lights) {  // patterns are unlit: no shadow pass
    m.shadow_pass(scene);
    m.timer.mark(Pass::shadow);
  } else {
    lights.counts.y = 0;
  }
  glNamedBufferSubData(m.lights_ubo.id(), 0, sizeof lights, &lights);
  glEnable(GL_FRAMEBUFFER_SRGB);

  // The eyes' fovea points as of the latch, after the left eye's full-resolution pass:
  // the right eye's could come later still, but both eyes show one gaze sample.
  std::array<EyeFoveation, 2> eyes = params.eyes;
  const bool blended = detail::has_forward_draws(scene);
  // Blended surfaces at the kept samples (BlendAt::samples): foveated methods in the
  // visibility pipeline.
  const bool blend_at_samples =
      blended && params.blend_at == BlendAt::samples && params.pipeline == Pipeline::visibility && params.method != Method::full;
  m.blend_counted = {false, false};
  bool accumulated = false;
  for (Eye e : kEyes) {
    const std::size_t i = static_cast<std::size_t>(e);
    const LensDistortion& lens = m.opt.model.distortion[i];
    const bool distort = m.opt.distortion && lens.enabled;
    const EyeView view = eye_view(scene, m.opt.model, e, camera->head, camera->ipd_mm);
    m.light_grid = glm::ivec4(0);
    if (file_lights && m.opt.light_tiles) {
      const LightTiles tiles = build_light_tiles(scene.lights, static_cast<std::size_t>(lights.counts.z), view.view_proj, m.eye_w, m.eye_h);
      glNamedBufferData(m.light_tiles_buffer.id(), static_cast<GLsizeiptr>(tiles.data.size() * sizeof(std::uint32_t)), tiles.data.data(),
                        GL_STREAM_DRAW);
      glTextureBuffer(m.light_tiles_texture.id(), GL_R32UI, m.light_tiles_buffer.id());
      m.light_grid = glm::ivec4(tiles.cols, tiles.rows, tiles.tile_px, 1);
    }
    if (Status s = m.full_resolution_pass(scene, view, params.pipeline); !s) return s.error();
    if (e == Eye::left) m.run_latch(latch, eyes, times);
    // The full method has no resolve pass to fold the lens into: it runs as RMFR at σ = 1
    // (the identity map), which is the same image.
    EyeFoveation eye_params = eyes[i];
    Method method = params.method;
    if (distort && method == Method::full) method = Method::rmfr, eye_params.sigma = 1.0;
    auto planned = plan_eye(method, eye_params, m.eye_w, m.eye_h, m.opt.model.eye(e));
    if (!planned) return Error{planned.error().kind, std::string(eye_name(e)) + " eye: " + planned.error().message};
    const EyePlan& plan = m.plans[i] = std::move(*planned);
    times.shaded_samples += plan.shaded_samples();
    const glm::ivec2 eye_origin(static_cast<int>(i) * m.eye_w, 0);

    // The regions each pass draws: the whole buffer, or one per layer of the atlas.
    const bool layered = !plan.layers.empty();
    std::vector<glm::ivec4> regions;
    if (layered)
      for (const Layer& l : plan.layers) regions.emplace_back(0, l.atlas_y, l.buffer_w, l.buffer_h);
    else
      regions.emplace_back(0, 0, plan.buffer_w, plan.buffer_h);
    const auto mapping = mapping_index(plan);
    if (!mapping) return mapping.error();
    const std::size_t variant = *mapping;
    if (Status s = m.ensure_variant(variant); !s) return s.error();
    // Temporal accumulation: RMFR's kernel in the visibility pipeline (docs/rmfr.md).
    const bool accumulate = params.temporal && temporal_applies(plan.method, params.pipeline);
    if (Status s = m.use_jitter(i, variant, accumulate); !s) return s.error();
    accumulated = accumulated || accumulate;

    // The eye's surface samples, through the frame's pipeline.
    const detail::SurfaceTargets* surface = nullptr;
    if (params.pipeline == Pipeline::visibility) {
      surface = m.visibility_surface(scene, view, plan, i, variant, regions);
    } else {
      auto g = m.gbuffer_surface(plan, i, variant, regions);
      if (!g) return g.error();
      surface = *g;
    }

    // alphaMode BLEND surfaces go over the eye's lit opaque result at output resolution.
    // Through the lens they must go on before it: the opaque result is resolved without
    // the lens into the eye's W×H blend target, blended there, and that is taken through
    // the lens by an identity resolve (one more full-resolution pass, only then).
    const bool blend_under_lens = distort && blended && !blend_at_samples;
    if (blend_under_lens) m.ensure_undistorted();
    const GLuint resolve_fbo = blend_under_lens ? m.undistorted->fbo.id() : m.output.fbo.id();
    const glm::ivec2 resolve_origin = blend_under_lens ? glm::ivec2(0) : eye_origin;
    auto blend_eye = [&]() -> Status {
      if (!blended || blend_at_samples) return {};  // at samples: composited before the inverse pass
      // llvmpipe runs the draws into one target as one scene, tile by tile, and stamps a
      // pass's end when its last tile is done: without a flush the previous pass's stamp
      // would fall after most of this pass (measured: the blend pass read 0 ms in full).
      glFlush();
      m.begin_blend_count(i);
      m.blend_pass(scene, view, resolve_fbo, blend_under_lens ? m.undistorted->texture.id() : m.output.texture.id(), resolve_origin,
                   m.opaque_depth(params.pipeline));
      glEndQuery(GL_SAMPLES_PASSED);
      if (blend_under_lens)
        if (Status s = m.resolve_full(plan, m.undistorted->texture.id(), m.output.fbo.id(), eye_origin, &lens); !s) return s;
      m.timer.mark(Pass::blend);
      return {};
    };

    if (plan.method == Method::full) {  // never through the lens (see above)
      glBindFramebuffer(GL_FRAMEBUFFER, m.output.fbo.id());
      glViewport(eye_origin.x, eye_origin.y, m.eye_w, m.eye_h);
      const GLuint lp = m.lighting_progs[0].id();
      set_mapping(lp, plan, glm::vec2(surface->width, surface->height));
      m.lighting_pass(lp, *surface, eye_origin, view);
      m.timer.mark(Pass::lighting);
      if (Status s = blend_eye(); !s) return s.error();
      continue;
    }

    m.ensure_reduced(i, plan.buffer_w, plan.buffer_h, layered);
    const detail::SurfaceTargets& tg = *surface;
    const detail::ColorTarget& rs = *m.reduced[i];
    const glm::vec2 texture_size(tg.width, tg.height);

    // Lighting on the reduced buffer.
    glBindFramebuffer(GL_FRAMEBUFFER, rs.fbo.id());
    const GLuint lp = m.lighting_progs[variant].id();
    set_mapping(lp, plan, texture_size);
    for (std::size_t r = 0; r < regions.size(); ++r) {
      glViewport(regions[r].x, regions[r].y, regions[r].z, regions[r].w);
      set(lp, "u_layer", static_cast<int>(r));
      m.lighting_pass(lp, tg, glm::ivec2(0), view);
    }
    m.timer.mark(Pass::lighting);
    if (blend_at_samples) {
      auto layers = m.samples_blend(scene, view, plan, i, variant, regions, texture_size, rs, times);
      if (!layers) return layers.error();
      times.blend_layers += *layers;
      m.timer.mark(Pass::blend);
    }

    // Resolve into this eye's half of the output; accumulation is RMFR's kernel only.
    const LensDistortion* through = distort && !blend_under_lens ? &lens : nullptr;
    if (Status s = accumulate ? m.temporal_resolve(i, plan, rs, tg, scene, view, resolve_fbo, resolve_origin, through)
                              : m.resolve_pass(plan, variant, rs, texture_size, resolve_fbo, resolve_origin, through);
        !s)
      return s.error();
    m.timer.mark(Pass::inverse);
    if (Status s = blend_eye(); !s) return s.error();
  }
  if (accumulated) m.temporal->next_frame();
  glFinish();
  times.gpu_done_ns = monotonic_now_ns();
  times.cpu = std::chrono::duration<double, std::milli>(Clock::now() - cpu_start).count();
  m.timer.collect(times);
  for (std::size_t i = 0; i < 2; ++i)
    if (m.blend_counted[i]) {
      GLuint64 n = 0;
      glGetQueryObjectui64v(m.blend_counts[i].id(), GL_QUERY_RESULT, &n);
      times.blend_samples += static_cast<std::size_t>(n);
    }
  if (m.transparent)
    for (std::size_t i = 0; i < 2; ++i) times.blend_samples += m.transparent->take_shaded(i);
  if (GLenum err = glGetError(); err != GL_NO_ERROR) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "OpenGL error 0x%04x during the frame", static_cast<unsigned>(err));
    return Error{ErrorKind::internal, buf};
  }
  return times;
}

image::Image Compositor::read_image() const {
  const Impl& m = *impl_;
  image::Image img(m.opt.width, m.opt.height);
  std::vector<std::uint8_t> rows(img.rgba.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  if (m.opt.float_output) {
    const std::vector<float> f = read_float();
    for (std::size_t k = 0; k < f.size(); ++k) {
      const float v = k % 4 == 3 ? f[k] : std::pow(std::fmin(std::fmax(f[k], 0.0f), 1.0f), 1.0f / 2.2f);
      rows[k] = static_cast<std::uint8_t>(std::lround(std::isfinite(v) ? v * 255.0f : 0.0f));
    }
  } else {
    glGetTextureImage(m.output.texture.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(rows.size()), rows.data());
  }
  const std::size_t stride = static_cast<std::size_t>(img.width) * 4;
  for (int y = 0; y < img.height; ++y)
    std::memcpy(img.at(0, y), rows.data() + static_cast<std::size_t>(img.height - 1 - y) * stride, stride);
  return img;
}

std::vector<float> Compositor::read_float() const {
  const Impl& m = *impl_;
  std::vector<float> px(static_cast<std::size_t>(m.opt.width) * static_cast<std::size_t>(m.opt.height) * 4);
  glGetTextureImage(m.output.texture.id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(px.size() * sizeof(float)), px.data());
  return px;
}

GLuint Compositor::output_framebuffer() const { return impl_->output.fbo.id(); }
int Compositor::width() const { return impl_->opt.width; }
int Compositor::height() const { return impl_->opt.height; }
int Compositor::eye_width() const { return impl_->eye_w; }
std::array<int, 2> Compositor::buffer_size(Eye e) const {
  const EyePlan& p = impl_->plans[static_cast<std::size_t>(e)];
  return {p.buffer_w, p.buffer_h};
}
const EyePlan& Compositor::plan(Eye e) const { return impl_->plans[static_cast<std::size_t>(e)]; }
void Compositor::reset_history() {
  if (impl_->temporal) impl_->temporal->reset();
}

std::string Compositor::shading_variant() const { return impl_->layout.variant_name(); }
std::size_t Compositor::gbuffer_bytes_per_pixel() const { return impl_->layout.bytes_per_pixel(); }
unsigned Compositor::material_features() const { return impl_->layout.features; }

std::string Compositor::renderer() const {
  auto str = [](GLenum e) {
    const auto* s = reinterpret_cast<const char*>(glGetString(e));
    return std::string(s ? s : "?");
  };
  return str(GL_VENDOR) + " / " + str(GL_RENDERER) + " / " + str(GL_VERSION);
}

}  // namespace foveal::render

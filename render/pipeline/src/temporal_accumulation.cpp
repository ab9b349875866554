#include "temporal_accumulation.hpp"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "compositor_impl.hpp"
#include "foveal/render/scene.hpp"
#include "foveal/render/stereo_camera.hpp"
#include "pass_uniforms.hpp"

namespace foveal::render::detail {

namespace {

// The current frame's smallest weight: a history of at most 16 frames, one jitter period.
constexpr float kMinBlend = 1.0f / 16.0f;

double halton(std::uint64_t index, std::uint64_t base) {
  double f = 1.0, r = 0.0;
  for (; index > 0; index /= base) {
    f /= static_cast<double>(base);
    r += f * static_cast<double>(index % base);
  }
  return r;
}

glm::dvec3 view_ray(const rmfr::Frustum& f, double x, double y) {
  return glm::normalize(glm::dvec3(f.tan_left + (f.tan_right - f.tan_left) * x, f.tan_bottom + (f.tan_top - f.tan_bottom) * y, -1.0));
}

}  // namespace

glm::vec2 temporal_jitter(std::uint64_t frame) {
  const std::uint64_t k = 1 + frame % 16;  // index 0 is (0, 0) in both bases: start at 1
  return {static_cast<float>(halton(k, 2) - 0.5), static_cast<float>(halton(k, 3) - 0.5)};
}

double fovea_step_deg(const rmfr::Plan& a, const rmfr::Plan& b) {
  const double c = glm::dot(view_ray(a.frustum, a.fovea_x, a.fovea_y), view_ray(b.frustum, b.fovea_x, b.fovea_y));
  return std::acos(std::fmin(1.0, std::fmax(-1.0, c))) * 180.0 / 3.14159265358979323846;
}

Result<TemporalAccumulation> TemporalAccumulation::create(const gl::ShaderLoader& shaders) {
  TemporalAccumulation t;
  auto p = shaders.program({{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "temporal/accumulate.frag"}}, "");
  if (!p) return p.error();
  t.program_ = std::move(*p);
  t.nearest_ = gl::make_clamped_sampler(GL_NEAREST);
  t.vao_ = gl::VertexArray::create();
  return t;
}

void TemporalAccumulation::reset() {
  for (EyeState& e : eyes_) e.valid = false;
}

GLuint TemporalAccumulation::accumulate(std::size_t eye, const rmfr::Plan& plan, GLuint reduced, GLuint depth, GLuint sample_depth, const EyeView& view) {
  EyeState& e = eyes_[eye];
  if (e.width != plan.screen_w || e.height != plan.screen_h) {
    for (History& h : e.history) {
      h.color = gl::make_texture_2d(GL_RGBA16F, plan.screen_w, plan.screen_h);
      h.depth = gl::make_texture_2d(GL_R32F, plan.screen_w, plan.screen_h);
      h.fbo = gl::Framebuffer::create();
      glNamedFramebufferTexture(h.fbo.id(), GL_COLOR_ATTACHMENT0, h.color.id(), 0);
      glNamedFramebufferTexture(h.fbo.id(), GL_COLOR_ATTACHMENT1, h.depth.id(), 0);
      const GLenum draw[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
      glNamedFramebufferDrawBuffers(h.fbo.id(), 2, draw);
    }
    e.width = plan.screen_w, e.height = plan.screen_h;
    e.valid = false;
  }
#ifndef FOVEAL_TEMPORAL_KEEP_HISTORY_AT_SACCADES
  // A saccade: the whole mapping moved under the history; the eye sees little during
  // it (saccadic suppression), so the frame after it starts over from its own samples.
  if (e.valid && fovea_step_deg(e.plan, plan) > kSaccadeDeg) e.valid = false;
#endif
  const History& past = e.history[static_cast<std::size_t>(e.written)];
  const History& next = e.history[static_cast<std::size_t>(1 - e.written)];

  const GLuint p = program_.id();
  set(p, "u_screen_size", glm::vec2(plan.screen_w, plan.screen_h));
  set(p, "u_buffer_size", glm::vec2(plan.buffer_w, plan.buffer_h));
  set(p, "u_fovea", glm::vec2(plan.fovea_x, plan.fovea_y));
  set(p, "u_f", glm::vec2(plan.fx, plan.fy));
  set(p, "u_jitter", jitter());
  const rmfr::Plan& prev = e.valid ? e.plan : plan;
  set(p, "u_prev_buffer_size", glm::vec2(prev.buffer_w, prev.buffer_h));
  set(p, "u_prev_fovea", glm::vec2(prev.fovea_x, prev.fovea_y));
  set(p, "u_prev_f", glm::vec2(prev.fx, prev.fy));
  set(p, "u_view_proj", view.view_proj);
  set(p, "u_inv_view_proj", view.inv_view_proj);
  set(p, "u_prev_view_proj", e.valid ? e.view_proj : view.view_proj);
  set(p, "u_history_valid", e.valid ? 1 : 0);
  set(p, "u_has_depth", depth != 0 ? 1 : 0);
  set(p, "u_min_blend", kMinBlend);

  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_CULL_FACE);
  glBindFramebuffer(GL_FRAMEBUFFER, next.fbo.id());
  glViewport(0, 0, plan.screen_w, plan.screen_h);
  glUseProgram(p);
  const GLuint textures[5] = {reduced, past.color.id(), past.depth.id(), depth, sample_depth};
  const GLuint n = nearest_.id(), samplers[5] = {n, n, n, n, n};  // every read is a texel fetch
  glBindTextures(0, 5, textures);
  glBindSamplers(0, 5, samplers);
  glBindVertexArray(vao_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindSamplers(0, 5, nullptr);

  e.written = 1 - e.written;
  e.valid = true;
  e.plan = plan;
  e.view_proj = view.view_proj;
  return next.color.id();
}

std::size_t TemporalAccumulation::bytes() const {
  std::size_t b = 0;
  for (const EyeState& e : eyes_) b += static_cast<std::size_t>(e.width) * static_cast<std::size_t>(e.height) * 2 * (8 + 4);
  return b;
}

}  // namespace foveal::render::detail

namespace foveal::render {

Status Compositor::Impl::use_jitter(std::size_t eye, std::size_t variant, bool on) {
  if (on && !temporal) {
    auto t = detail::TemporalAccumulation::create(shaders);
    if (!t) return t.error();
    temporal.emplace(std::move(*t));
  }
  if (!on && temporal) temporal->drop(eye);  // a later frame with it starts afresh
  const glm::vec2 j = on ? temporal->jitter() : glm::vec2(0.0f);
  visibility->set_jitter(variant, j);
  detail::set(lighting_progs[variant].id(), "u_jitter", j);
  return {};
}

Status Compositor::Impl::temporal_resolve(std::size_t eye, const EyePlan& plan, const detail::ColorTarget& lit,
                                          const detail::SurfaceTargets& surface, const Scene& scene, const EyeView& view,
                                          GLuint fbo, glm::ivec2 origin, const LensDistortion* lens) {
  const GLuint frame = temporal->accumulate(eye, rmfr_plan(plan), lit.texture.id(),
                                            scene.is_pattern() ? 0 : visibility->depth_texture(), surface.depth.id(), view);
  return resolve_full(plan, frame, fbo, origin, lens);  // the accumulated frame is full resolution
}

}  // namespace foveal::render

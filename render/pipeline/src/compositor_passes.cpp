// The compositor's passes, each as it runs for one eye: shadow, the full-resolution pass
// (G-buffer or visibility), the surface (mapping or material pass), lighting, the late
// latch between them, and the blend pass for alphaMode BLEND. Their order: render() in
// compositor.cpp.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "compositor_impl.hpp"
#include "foveal/render/light_rig.hpp"
#include "foveal/render/scene.hpp"
#include "foveal/rmfr_mapping.hpp"

namespace foveal::render {

namespace {

using detail::Pass;
using detail::set;

}  // namespace

void Compositor::Impl::draw_geometry(const Scene& scene, const EyeView& v) {
  const GLuint p = gbuffer_prog.id();
  glUseProgram(p);
  set(p, "u_view_proj", v.view_proj);
  for (const DrawItem& d : scene.draws) {
    const Primitive& prim = scene.primitives[static_cast<std::size_t>(d.primitive)];
    const Material& mat = detail::material_of(scene, prim.material);
    if (mat.forward()) continue;  // the forward pass draws it over the lit result
    set(p, "u_model", d.world);
    set(p, "u_normal_matrix", glm::mat3(glm::transpose(glm::inverse(d.world))));
    detail::set_material(p, scene, mat);
    glBindVertexArray(prim.vao.id());
    glDrawElements(GL_TRIANGLES, prim.index_count, GL_UNSIGNED_INT, nullptr);
  }
}

void Compositor::Impl::draw_pattern(const Scene& scene) {
  const GLuint p = pattern_prog.id();
  glUseProgram(p);
  set(p, "u_viewport_origin", glm::vec2(0));
  set(p, "u_viewport_size", glm::vec2(eye_w, eye_h));
  set(p, "u_angle", glm::radians(scene.pattern->angle_deg));
  set(p, "u_tile_px", scene.pattern->tile_px);
  glBindTextureUnit(0, scene.pattern->texture.id());
  glBindVertexArray(empty_vao.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void Compositor::Impl::shadow_pass(const Scene& scene) {
  glBindFramebuffer(GL_FRAMEBUFFER, shadow.fbo.id());
  glViewport(0, 0, shadow.width, shadow.height);
  glEnable(GL_DEPTH_TEST);
  glClear(GL_DEPTH_BUFFER_BIT);
  const GLuint p = shadow_prog.id();
  glUseProgram(p);
  set(p, "u_light_matrix", sun_clip_matrix(scene.bounds));
  for (const DrawItem& d : scene.draws) {
    const Primitive& prim = scene.primitives[static_cast<std::size_t>(d.primitive)];
    // Blended surfaces cast no shadow: an opaque one from a pane of glass would be
    // wrong, and a partial one needs a translucent shadow map (docs/scenes.md).
    if (detail::material_of(scene, prim.material).forward()) continue;
    set(p, "u_model", d.world);
    glBindVertexArray(prim.vao.id());
    glDrawElements(GL_TRIANGLES, prim.index_count, GL_UNSIGNED_INT, nullptr);
  }
}

// An eye's full-resolution pass, the first of its surface and the last that does not
// depend on the fovea: the G-buffer, or the visibility pass.
Status Compositor::Impl::full_resolution_pass(const Scene& scene, const EyeView& view, Pipeline pipeline) {
  if (pipeline == Pipeline::visibility) {
    visibility->visibility_pass(scene, view);
    timer.mark(Pass::gbuffer);
    return {};
  }
  auto g = gbuffer_targets();
  if (!g) return g.error();
  glBindFramebuffer(GL_FRAMEBUFFER, (*g)->fbo.id());
  glViewport(0, 0, eye_w, eye_h);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glClearColor(0, 0, 0, 0);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (scene.is_pattern()) draw_pattern(scene);
  else draw_geometry(scene, view);
  glDisable(GL_DEPTH_TEST);
  timer.mark(Pass::gbuffer);
  return {};
}

// The G-buffer pipeline's surface for one eye after its full-resolution pass: the
// G-buffer itself for full, else mapped into the eye's transformed buffer.
Result<const detail::SurfaceTargets*> Compositor::Impl::gbuffer_surface(const EyePlan& plan, std::size_t eye, std::size_t variant,
                                                                        const std::vector<glm::ivec4>& regions) {
  auto g = gbuffer_targets();
  if (!g) return g.error();
  if (plan.method == Method::full) return *g;

  // Mapping: G-buffer -> reduced G-buffer; RMFR's (also full through the lens) is foveal-rmfr's.
  ensure_transformed(eye, plan.buffer_w, plan.buffer_h, !plan.layers.empty());
  const detail::SurfaceTargets& tg = *transformed[eye];
  if (mapping_kernel(variant).rmfr_passes) {  // RMFR's kernel: rmfr, and uniform and fixed as plans on it
    if (Status s = foveator->map(rmfr_plan(plan), (*g)->textures(), tg.fbo.id()); !s) return s.error();
    timer.mark(Pass::mapping);
    return &tg;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, tg.fbo.id());
  const GLuint mp = map_progs[variant].id();
  glUseProgram(mp);
  set_mapping(mp, plan, glm::vec2(tg.width, tg.height));
  (*g)->bind_textures();
  glBindVertexArray(empty_vao.id());
  for (std::size_t r = 0; r < regions.size(); ++r) {
    glViewport(regions[r].x, regions[r].y, regions[r].z, regions[r].w);
    set(mp, "u_layer", static_cast<int>(r));
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  timer.mark(Pass::mapping);
  return &tg;
}

// The visibility pipeline's surface for one eye after its visibility pass: the
// material at the samples the plan keeps (W×H for full).
const detail::SurfaceTargets* Compositor::Impl::visibility_surface(const Scene& scene, const EyeView& view, const EyePlan& plan,
                                                                   std::size_t eye, std::size_t variant,
                                                                   const std::vector<glm::ivec4>& regions) {
  detail::MaterialSurface& dst = plan.method == Method::full
                                           ? visibility->full_surface()
                                           : visibility->eye_surface(eye, plan.buffer_w, plan.buffer_h, !plan.layers.empty());
  visibility->material_pass(scene, view, plan, variant, regions, dst);
  timer.mark(Pass::mapping);
  return &dst.surface;
}

// Late latch: the GPU finishes the passes so far (a fence), then the latch reads the
// newest fovea; only the eyes' fovea points are taken from it.
void Compositor::Impl::run_latch(const FoveaLatch& latch, std::array<EyeFoveation, 2>& eyes, PassTimes& times) {
  if (latch) {
    GLsync fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, 1'000'000'000);
    glDeleteSync(fence);
    std::array<EyeFoveation, 2> latched = eyes;
    latch(latched);
    for (std::size_t i = 0; i < eyes.size(); ++i)
      if (std::isfinite(latched[i].fovea_x) && std::isfinite(latched[i].fovea_y)) {
        eyes[i].fovea_x = std::clamp(latched[i].fovea_x, 0.0, 1.0);
        eyes[i].fovea_y = std::clamp(latched[i].fovea_y, 0.0, 1.0);
      }
  }
  times.latch_ns = monotonic_now_ns();
}

// Lighting from `src` (G-buffer or reduced buffer) into the bound framebuffer, with
// the mapping uniforms already set on the program.
void Compositor::Impl::lighting_pass(GLuint p, const detail::SurfaceTargets& src, glm::ivec2 origin, const EyeView& v) {
  glUseProgram(p);
  set(p, "u_origin", origin);
  set(p, "u_inv_view_proj", v.inv_view_proj);
  set(p, "u_camera_pos", v.position);
  set(p, "u_light_grid", light_grid);
  src.bind_textures();
  glBindTextureUnit(5, shadow.texture.id());
  glBindTextureUnit(7, light_tiles_texture.id());
  glBindTextureUnit(11, sheen_albedo.id());
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, lights_ubo.id());
  glBindVertexArray(empty_vao.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

// The eye's lit reduced buffer `lit` taken to W×H by the plan's kernel (mapping variant
// `variant`, which sees `texture_size` texels) into the viewport at `origin` of `fbo`,
// through `lens` when given. KFR's angle axis wraps around.
Status Compositor::Impl::resolve_pass(const EyePlan& plan, std::size_t variant, const detail::ColorTarget& lit, glm::vec2 texture_size,
                                      GLuint fbo, glm::ivec2 origin, const LensDistortion* lens) {
  if (mapping_kernel(variant).rmfr_passes) {  // RMFR's kernel (rmfr, uniform, fixed): foveal-rmfr's resolve
    const rmfr::Lens l = lens ? rmfr_lens(*lens) : rmfr::Lens{};
    return foveator->resolve(rmfr_plan(plan), lit.texture.id(), fbo, origin.x, origin.y, lens ? &l : nullptr);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(origin.x, origin.y, eye_w, eye_h);
  glTextureParameteri(lit.texture.id(), GL_TEXTURE_WRAP_T, mapping_kernel(variant).repeats_v ? GL_REPEAT : GL_CLAMP_TO_EDGE);
  const GLuint p = resolve_progs[variant][lens ? 1 : 0].id();
  glUseProgram(p);
  set_mapping(p, plan, texture_size);
  set(p, "u_origin", origin);
  if (lens) {
    set(p, "u_lens_center", glm::vec2(lens->center.x, 1.0f - lens->center.y));
    set(p, "u_lens_k", glm::vec3(lens->k1, lens->k2, lens->k3));
    set(p, "u_lens_scale", lens->channel_scale);
  }
  glBindTextureUnit(0, lit.texture.id());
  glBindVertexArray(empty_vao.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  return {};
}

// A full-resolution (W×H) image of the eye, `texture`, into the viewport at `origin` of
// `fbo`: foveal-rmfr's resolve at σ = 1 copies it (pixel centres, exact) and takes it
// through `lens` when given.
Status Compositor::Impl::resolve_full(const EyePlan& plan, GLuint texture, GLuint fbo, glm::ivec2 origin, const LensDistortion* lens) {
  rmfr::Plan identity = rmfr_plan(plan);
  identity.buffer_w = identity.screen_w, identity.buffer_h = identity.screen_h;
  identity.sigma = 1.0;
  identity.fx = identity.fy = rmfr::kRmfrIdentityF;
  const rmfr::Lens l = lens ? rmfr_lens(*lens) : rmfr::Lens{};
  return foveator->resolve(identity, texture, fbo, origin.x, origin.y, lens ? &l : nullptr);
}

// alphaMode BLEND, after the eye's lit opaque result is complete in the output: each
// blended draw shaded forward at output resolution, back to front by the distance of
// its bounds' centre from the eye, composited "over" it (straight alpha), tested
// against the eye's opaque depth `depth` (W×H) without writing depth, into the eye's
// viewport at `origin` of `fbo`.
// Transmission shows the opaque result behind: a mipmapped copy of the eye's region of
// `color` at `origin` (the roughness blurs by level).
void Compositor::Impl::copy_behind(GLuint color, glm::ivec2 origin) {
  ensure_behind();
  glCopyImageSubData(color, GL_TEXTURE_2D, 0, origin.x, origin.y, 0, behind->texture.id(), GL_TEXTURE_2D, 0, 0, 0, 0, eye_w, eye_h, 1);
  glGenerateTextureMipmap(behind->texture.id());
}

void Compositor::Impl::blend_pass(const Scene& scene, const EyeView& v, GLuint fbo, GLuint color, glm::ivec2 origin, GLuint depth) {
  std::vector<std::pair<float, std::size_t>> order;  // (distance, draw)
  for (std::size_t i = 0; i < scene.draws.size(); ++i) {
    const DrawItem& d = scene.draws[i];
    const Primitive& prim = scene.primitives[static_cast<std::size_t>(d.primitive)];
    if (!detail::material_of(scene, prim.material).forward()) continue;
    const glm::vec3 centre(d.world * glm::vec4(prim.local_bounds.center(), 1.0f));
    order.emplace_back(glm::length(centre - v.position), i);
  }
  if (order.empty()) return;
  const bool transmission = (layout.features & feature_transmission) != 0;
  if (transmission) copy_behind(color, origin);
  // Farthest first; equal distances keep the file's order.
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(origin.x, origin.y, eye_w, eye_h);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  const GLuint p = blend_prog.id();
  glUseProgram(p);
  set(p, "u_view_proj", v.view_proj);
  set(p, "u_inv_view_proj", v.inv_view_proj);
  set(p, "u_camera_pos", v.position);
  set(p, "u_origin", origin);
  set(p, "u_eye_size", glm::vec2(eye_w, eye_h));
  set(p, "u_light_grid", light_grid);
  glBindTextureUnit(7, light_tiles_texture.id());
  glBindTextureUnit(11, sheen_albedo.id());
  glBindTextureUnit(12, transmission ? behind->texture.id() : 0);
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, lights_ubo.id());
  for (const auto& [distance, i] : order) {
    const DrawItem& d = scene.draws[i];
    const Primitive& prim = scene.primitives[static_cast<std::size_t>(d.primitive)];
    const Material& mat = detail::material_of(scene, prim.material);
    set(p, "u_model", d.world);
    set(p, "u_normal_matrix", glm::mat3(glm::transpose(glm::inverse(d.world))));
    set(p, "u_model_scale", glm::vec3(glm::length(glm::vec3(d.world[0])), glm::length(glm::vec3(d.world[1])), glm::length(glm::vec3(d.world[2]))));
    detail::set_material(p, scene, mat);
    glBindTextureUnit(5, shadow.texture.id());
    glBindTextureUnit(6, depth);
    detail::set_culling(mat, d.world);
    glBindVertexArray(prim.vao.id());
    glDrawElements(GL_TRIANGLES, prim.index_count, GL_UNSIGNED_INT, nullptr);
  }
  glDisable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
  glDisable(GL_BLEND);
}

}  // namespace foveal::render

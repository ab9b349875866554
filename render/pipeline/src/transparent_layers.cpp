// Transparency at the kept samples (transparent_layers.hpp; docs/rmfr.md): the peel at
// W×H, the composite in the reduced buffer, and the compositor's step that runs them for
// one eye between its lighting and inverse passes.
#include "transparent_layers.hpp"

#include <algorithm>
#include <vector>

#include <glm/glm.hpp>

#include "compositor_impl.hpp"
#include "foveal/render/scene.hpp"
#include "foveal/render/stereo_camera.hpp"
#include "pass_uniforms.hpp"

namespace foveal::render::detail {

Status TransparentLayers::ensure_programs(const gl::ShaderLoader& shaders, std::size_t variant, const std::string& lit_defines) {
  if (lit_defines != lit_defines_ || composite_progs_.size() != mapping_variant_count()) {
    composite_progs_.clear();
    composite_progs_.resize(mapping_variant_count());
    classify_progs_.clear();
    classify_progs_.resize(mapping_variant_count());
    lit_defines_ = lit_defines;
  }
  if (!peel_prog_) {
    auto p = shaders.program({{GL_VERTEX_SHADER, "gbuffer.vert"}, {GL_FRAGMENT_SHADER, "transparent_peel.frag"}}, "");
    if (!p) return p.error();
    peel_prog_ = std::move(*p);
    empty_vao_ = gl::VertexArray::create();
  }
  if (!composite_progs_[variant]) {
    auto p = shaders.program({{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "transparent_layer.frag"}}, lit_defines,
                             mapping_files(variant));
    if (!p) return p.error();
    composite_progs_[variant] = std::move(*p);
    auto q = shaders.program({{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "transparent_layer.frag"}}, "#define CLASSIFY 1\n",
                             mapping_files(variant));
    if (!q) return q.error();
    classify_progs_[variant] = std::move(*q);
  }
  return {};
}

int TransparentLayers::peel(const Scene& scene, const glm::mat4& view_proj, GLuint opaque_depth, int width, int height,
                            std::size_t& dropped) {
  std::vector<std::size_t> draws;
  for (std::size_t i = 0; i < scene.draws.size(); ++i)
    if (material_of(scene, scene.primitives[static_cast<std::size_t>(scene.draws[i].primitive)].material).forward()) draws.push_back(i);
  if (draws.empty()) return 0;
  if (!any_) {
    any_ = gl::make_query(GL_ANY_SAMPLES_PASSED);
    count_ = gl::make_query(GL_SAMPLES_PASSED);
  }
  const GLuint p = peel_prog_.id();
  glUseProgram(p);
  set(p, "u_view_proj", view_proj);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  int taken = 0;
  // Front to back: layer k is the nearest surface behind layer k-1. One more peel past the
  // cap only counts what the cap leaves out.
  for (int k = 0; k <= kMaxLayers; ++k) {
    std::optional<VisibilityTarget>& t = layers_[static_cast<std::size_t>(k)];
    if (!t || t->width != width || t->height != height) t = VisibilityTarget::create(width, height);
    const GLuint none[4] = {0, 0, 0, 0};
    glClearNamedFramebufferuiv(t->fbo.id(), GL_COLOR, 0, none);
    glCopyImageSubData(opaque_depth, GL_TEXTURE_2D, 0, 0, 0, 0, t->depth.id(), GL_TEXTURE_2D, 0, 0, 0, 0, width, height, 1);
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo.id());
    glViewport(0, 0, width, height);
    set(p, "u_first", k == 0 ? 1 : 0);
    glBindTextureUnit(6, k == 0 ? 0 : layers_[static_cast<std::size_t>(k - 1)]->depth.id());
    const bool counting = k == kMaxLayers;
    const GLenum target = counting ? GL_SAMPLES_PASSED : GL_ANY_SAMPLES_PASSED;
    const GLuint query = counting ? count_.id() : any_.id();
    glBeginQuery(target, query);
    for (std::size_t i : draws) {
      const DrawItem& d = scene.draws[i];
      const Primitive& prim = scene.primitives[static_cast<std::size_t>(d.primitive)];
      set_culling(material_of(scene, prim.material), d.world);  // as the blend pass culls
      set(p, "u_model", d.world);
      set(p, "u_normal_matrix", glm::mat3(glm::transpose(glm::inverse(d.world))));
      set(p, "u_draw", static_cast<unsigned>(i));
      glBindVertexArray(prim.vao.id());
      glDrawElements(GL_TRIANGLES, prim.index_count, GL_UNSIGNED_INT, nullptr);
    }
    glEndQuery(target);
    // The next peel depends on whether this one found anything: a wait for this peel.
    GLuint result = 0;
    glGetQueryObjectuiv(query, GL_QUERY_RESULT, &result);
    if (counting) dropped += result;
    if (counting || result == 0) break;
    ++taken;
  }
  glDisable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
  glDisable(GL_DEPTH_TEST);
  glBindTextureUnit(6, 0);
  return taken;
}

void TransparentLayers::composite(const Scene& scene, const EyeView& view, const EyePlan& plan, std::size_t variant,
                                  const std::vector<glm::ivec4>& regions, glm::vec2 texture_size, glm::ivec4 light_grid, int layers,
                                  const ColorTarget& target, std::size_t eye) {
  // The forward materials the draws use, as DrawRecord::material numbers them (the default last).
  std::vector<std::size_t> materials;
  for (const DrawItem& d : scene.draws) {
    const int m = scene.primitives[static_cast<std::size_t>(d.primitive)].material;
    const std::size_t slot = m >= 0 ? static_cast<std::size_t>(m) : scene.materials.size();
    if (material_of(scene, m).forward() && std::find(materials.begin(), materials.end(), slot) == materials.end())
      materials.push_back(slot);
  }
  if (!fbo_) fbo_ = gl::Framebuffer::create();
  if (depth_w_ < target.width || depth_h_ < target.height) {
    depth_w_ = std::max(depth_w_, target.width), depth_h_ = std::max(depth_h_, target.height);
    depth_ = gl::make_texture_2d(GL_DEPTH_COMPONENT32F, depth_w_, depth_h_);
    glNamedFramebufferTexture(fbo_.id(), GL_DEPTH_ATTACHMENT, depth_.id(), 0);
  }
  glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, target.texture.id(), 0);
  glNamedFramebufferDrawBuffer(fbo_.id(), GL_COLOR_ATTACHMENT0);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());

  const GLuint c = classify_progs_[variant].id(), p = composite_progs_[variant].id();
  set_mapping(c, plan, texture_size);
  set_mapping(p, plan, texture_size);
  set(p, "u_view_proj", view.view_proj);
  set(p, "u_camera_pos", view.position);
  set(p, "u_light_grid", light_grid);
  const SceneGeometry& geo = scene.geometry;
  const GLuint geometry[3] = {geo.vertex_pairs.id(), geo.triangles.id(), geo.draw_floats.id()};
  glBindTextures(8, 3, geometry);
  glBindTextureUnit(13, geo.draw_uints.id());  // transparent_layer.frag's DRAW_UINTS_UNIT
  glBindVertexArray(empty_vao_.id());
  glEnable(GL_DEPTH_TEST);
  auto draw_regions = [&](GLuint prog) {
    for (std::size_t r = 0; r < regions.size(); ++r) {
      glViewport(regions[r].x, regions[r].y, regions[r].z, regions[r].w);
      set(prog, "u_layer", static_cast<int>(r));
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  };
  for (int k = layers - 1; k >= 0; --k) {  // deepest first: "over" is back to front
    glBindTextureUnit(6, layers_[static_cast<std::size_t>(k)]->ids.id());
    // Classification: each texel's material in this layer into the depth (1: none).
    const float far = 1.0f;
    glClearNamedFramebufferfv(fbo_.id(), GL_DEPTH, 0, &far);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_ALWAYS);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glUseProgram(c);
    gl::Query& q = shaded_[eye][static_cast<std::size_t>(k)];
    if (!q) q = gl::make_query(GL_SAMPLES_PASSED);
    glBeginQuery(GL_SAMPLES_PASSED, q.id());
    draw_regions(c);
    glEndQuery(GL_SAMPLES_PASSED);
    // Each material at its depth, EQUAL: shaded on its own texels only. A layer's texels
    // of different materials are disjoint: their order does not matter.
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_EQUAL);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glUseProgram(p);
    for (std::size_t m : materials) {
      const Material& mat = material_of(scene, m < scene.materials.size() ? static_cast<int>(m) : -1);
      set_material(p, scene, mat);
      for (int slot = 0; slot < Material::slot_count; ++slot) {
        const int t = mat.texture(static_cast<Material::Slot>(slot));
        glBindSampler(material_texture_unit(slot), t >= 0 ? scene.isotropic_samplers[static_cast<std::size_t>(t)].id() : 0);
      }
      const float z = material_depth(m);
      glDepthRangef(z, z);
      draw_regions(p);
    }
    glDepthRangef(0.0f, 1.0f);
  }
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glDisable(GL_DEPTH_TEST);
  for (int slot = 0; slot < Material::slot_count; ++slot) glBindSampler(material_texture_unit(slot), 0);
  glBindTextures(8, 3, nullptr);
  glBindTextureUnit(13, 0);
  glBindTextureUnit(6, 0);
  shaded_layers_[eye] = layers;
}

std::size_t TransparentLayers::take_shaded(std::size_t eye) {
  std::size_t n = 0;
  for (int k = 0; k < shaded_layers_[eye]; ++k) {
    GLuint64 r = 0;
    glGetQueryObjectui64v(shaded_[eye][static_cast<std::size_t>(k)].id(), GL_QUERY_RESULT, &r);
    n += static_cast<std::size_t>(r);
  }
  shaded_layers_[eye] = 0;
  return n;
}

std::size_t TransparentLayers::bytes() const {
  std::size_t b = 0;
  for (const auto& l : layers_)
    if (l) b += l->bytes();
  return b;
}

}  // namespace foveal::render::detail

namespace foveal::render {

// One eye's blended surfaces at its kept samples, over its lit reduced buffer `target`,
// before its inverse pass. Returns the layers composited.
Result<int> Compositor::Impl::samples_blend(const Scene& scene, const EyeView& view, const EyePlan& plan, std::size_t eye,
                                            std::size_t variant, const std::vector<glm::ivec4>& regions, glm::vec2 texture_size,
                                            const detail::ColorTarget& target, PassTimes& times) {
  if (!transparent) transparent.emplace();
  if (Status s = transparent->ensure_programs(shaders, variant, lit_defines); !s) return s.error();
  // llvmpipe stamps a pass's end when its target's last tile is done: flush the lighting
  // pass so that its stamp is not charged here (as the blend pass does).
  glFlush();
  const int layers = transparent->peel(scene, view.view_proj, visibility->depth_texture(), eye_w, eye_h, times.blend_dropped);
  if (layers == 0) return 0;
  // What transmission sees: the eye's opaque samples resolved to W×H, as the output path
  // copies its output (under accumulation, this frame's jittered grid without the history).
  const bool transmission = (layout.features & feature_transmission) != 0;
  if (transmission) {
    ensure_behind();
    if (Status s = resolve_pass(plan, variant, target, texture_size, behind->fbo.id(), glm::ivec2(0), nullptr); !s) return s.error();
    glGenerateTextureMipmap(behind->texture.id());
  }
  glBindTextureUnit(12, transmission ? behind->texture.id() : 0);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glBindTextureUnit(5, shadow.texture.id());
  glBindTextureUnit(7, light_tiles_texture.id());
  glBindTextureUnit(11, sheen_albedo.id());
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, lights_ubo.id());
  transparent->composite(scene, view, plan, variant, regions, texture_size, light_grid, layers, target, eye);
  glDisable(GL_BLEND);
  glBindTextureUnit(12, 0);
  return layers;
}

void Compositor::Impl::begin_blend_count(std::size_t eye) {
  if (!blend_counts[eye]) blend_counts[eye] = gl::make_query(GL_SAMPLES_PASSED);
  blend_counted[eye] = true;
  glBeginQuery(GL_SAMPLES_PASSED, blend_counts[eye].id());
}

}  // namespace foveal::render

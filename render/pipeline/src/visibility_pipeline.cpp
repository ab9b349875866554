#include "visibility_pipeline.hpp"

#include <algorithm>
#include <optional>
#include <string>

#include <glm/matrix.hpp>

#include "foveal/render/scene.hpp"
#include "foveal/render/stereo_camera.hpp"
#include "pass_uniforms.hpp"

namespace foveal::render::detail {

namespace {

// The material passes' tiles (texels a side) and the material slots with a tile list of
// their own; materials past the last slot share its list (shaders/common/material_tiles.glsl).
constexpr int kMaterialTile = 32;
constexpr std::size_t kMaterialSlots = 1024;
std::string tile_defines() {
  return "#define MATERIAL_TILE " + std::to_string(kMaterialTile) + "\n#define MATERIAL_SLOTS " + std::to_string(kMaterialSlots) + "\n";
}

// Which material slots (Scene::materials, then the default) any draw uses.
std::vector<std::size_t> used_materials(const Scene& scene) {
  std::vector<bool> used(scene.materials.size() + 1, false);
  for (const DrawItem& d : scene.draws) {
    const int m = scene.primitives[static_cast<std::size_t>(d.primitive)].material;
    if (material_of(scene, m).forward()) continue;  // never in the visibility target
    used[m >= 0 ? static_cast<std::size_t>(m) : scene.materials.size()] = true;
  }
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < used.size(); ++i)
    if (used[i]) out.push_back(i);
  return out;
}

MaterialSurface& ensure(std::optional<MaterialSurface>& slot, int w, int h, bool grow_only, const SurfaceLayout& layout) {
  if (auto size = realloc_size(slot.has_value(), slot ? slot->width() : 0, slot ? slot->height() : 0, w, h, grow_only))
    slot = MaterialSurface::create(size->first, size->second, layout);
  return *slot;
}

Status build_program(const gl::ShaderLoader& shaders, gl::Program& out, const std::vector<gl::ShaderStage>& stages,
                     const std::string& defines, const std::vector<gl::VirtualFile>& files = {}) {
  auto p = shaders.program(stages, defines, files);
  if (!p) return p.error();
  out = std::move(*p);
  return {};
}

}  // namespace

Result<VisibilityPipeline> VisibilityPipeline::create(const gl::ShaderLoader& shaders, int eye_width, int eye_height) {
  VisibilityPipeline v;
  v.eye_w_ = eye_width;
  v.eye_h_ = eye_height;
  auto build = [&](gl::Program& out, std::vector<gl::ShaderStage> stages, const std::string& defines) {
    return build_program(shaders, out, stages, defines);
  };
  const gl::ShaderStage geometry{GL_VERTEX_SHADER, "gbuffer.vert"}, visibility{GL_FRAGMENT_SHADER, "visibility.frag"};
  if (Status s = build(v.visibility_prog_, {geometry, visibility}, ""); !s) return s.error();
  if (Status s = build(v.visibility_mask_prog_, {geometry, visibility}, "#define ALPHA_MASK 1\n"); !s) return s.error();
  const gl::ShaderStage fullscreen{GL_VERTEX_SHADER, "fullscreen.vert"};
  v.classify_progs_.resize(mapping_variant_count());
  v.pattern_progs_.resize(mapping_variant_count());
  v.material_progs_.resize(mapping_variant_count());
  for (std::size_t m = 0; m < mapping_variant_count(); ++m) {
    if (!mapping_kernel(m).built_up_front) continue;  // ensure_mapping, on first use
    if (Status s = build_program(shaders, v.classify_progs_[m], {fullscreen, {GL_FRAGMENT_SHADER, "classify.frag"}}, "", mapping_files(m)); !s)
      return s.error();
    if (Status s = build_program(shaders, v.pattern_progs_[m], {fullscreen, {GL_FRAGMENT_SHADER, "material.frag"}}, "#define PATTERN 1\n",
                                 mapping_files(m));
        !s)
      return s.error();
  }
  if (Status s = v.use_layout(shaders, SurfaceLayout{}); !s) return s.error();
  if (Status s = build(v.tiles_prog_, {{GL_COMPUTE_SHADER, "material_tiles.comp"}}, tile_defines()); !s) return s.error();
  v.empty_vao_ = gl::VertexArray::create();
  return v;
}

Status VisibilityPipeline::use_layout(const gl::ShaderLoader& shaders, const SurfaceLayout& layout) {
  for (std::size_t m = 0; m < material_progs_.size(); ++m) {
    material_progs_[m].reset();  // the kernels not built up front: rebuilt on use
    if (mapping_kernel(m).built_up_front)
      if (Status s = build_program(shaders, material_progs_[m], {{GL_VERTEX_SHADER, "material_tile.vert"}, {GL_FRAGMENT_SHADER, "material.frag"}},
                                   tile_defines() + layout.defines(), mapping_files(m));
          !s)
        return s;
  }
  layout_ = layout;
  full_.reset();
  for (auto& e : eyes_) e.reset();
  return {};
}

Status VisibilityPipeline::ensure_mapping(const gl::ShaderLoader& shaders, std::size_t m) {
  if (mapping_kernel(m).built_up_front) return {};
  const std::vector<gl::VirtualFile> files = mapping_files(m);
  const gl::ShaderStage fullscreen{GL_VERTEX_SHADER, "fullscreen.vert"};
  if (!classify_progs_[m])
    if (Status s = build_program(shaders, classify_progs_[m], {fullscreen, {GL_FRAGMENT_SHADER, "classify.frag"}}, "", files); !s)
      return s;
  if (!pattern_progs_[m])
    if (Status s = build_program(shaders, pattern_progs_[m], {fullscreen, {GL_FRAGMENT_SHADER, "material.frag"}},
                                 "#define PATTERN 1\n", files);
        !s)
      return s;
  if (!material_progs_[m])
    if (Status s = build_program(shaders, material_progs_[m], {{GL_VERTEX_SHADER, "material_tile.vert"}, {GL_FRAGMENT_SHADER, "material.frag"}},
                                 tile_defines() + layout_.defines(), files);
        !s)
      return s;
  return {};
}

void VisibilityPipeline::set_jitter(std::size_t m, glm::vec2 jitter) {
  for (const gl::Program* p : {&classify_progs_[m], &material_progs_[m], &pattern_progs_[m]})
    if (*p) set(p->id(), "u_jitter", jitter);
}

void VisibilityPipeline::visibility_pass(const Scene& scene, const EyeView& view) {
  if (!visibility_) visibility_ = VisibilityTarget::create(eye_w_, eye_h_);
  if (scene.is_pattern()) return;
  const GLuint fbo = visibility_->fbo.id();
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(0, 0, eye_w_, eye_h_);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  const GLuint none[4] = {0, 0, 0, 0};
  const float far = 1.0f;
  glClearNamedFramebufferuiv(fbo, GL_COLOR, 0, none);
  glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &far);
  for (GLuint p : {visibility_prog_.id(), visibility_mask_prog_.id()}) set(p, "u_view_proj", view.view_proj);
  for (std::size_t i = 0; i < scene.draws.size(); ++i) {
    const DrawItem& d = scene.draws[i];
    const Primitive& prim = scene.primitives[static_cast<std::size_t>(d.primitive)];
    const Material& m = material_of(scene, prim.material);
    if (m.forward()) continue;  // the compositor's forward pass draws it over the lit result
    const bool masked = m.alpha_cutoff >= 0.0f;
    const GLuint p = masked ? visibility_mask_prog_.id() : visibility_prog_.id();
    glUseProgram(p);
    set(p, "u_model", d.world);
    set(p, "u_normal_matrix", glm::mat3(glm::transpose(glm::inverse(d.world))));
    set(p, "u_draw", static_cast<unsigned>(i));
    if (masked) set_material(p, scene, m);
    glBindVertexArray(prim.vao.id());
    glDrawElements(GL_TRIANGLES, prim.index_count, GL_UNSIGNED_INT, nullptr);
  }
  glDisable(GL_DEPTH_TEST);
}

void VisibilityPipeline::material_pass(const Scene& scene, const EyeView& view, const EyePlan& plan, std::size_t mapping,
                                       const std::vector<glm::ivec4>& regions, MaterialSurface& dst) {
  const GLuint fbo = dst.surface.fbo.id();
  const glm::vec2 texture_size(dst.width(), dst.height());
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  // What a G-buffer holds where nothing was drawn: zero, depth 1.
  const float zero[4] = {0, 0, 0, 0}, far[4] = {1, 1, 1, 1};
  for (GLint b = 0; b < 4; ++b) glClearNamedFramebufferfv(fbo, GL_COLOR, b, zero);
  glClearNamedFramebufferfv(fbo, GL_COLOR, 4, far);
  glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, far);
  glBindVertexArray(empty_vao_.id());
  auto draw_regions = [&](GLuint p) {
    for (std::size_t r = 0; r < regions.size(); ++r) {
      glViewport(regions[r].x, regions[r].y, regions[r].z, regions[r].w);
      set(p, "u_layer", static_cast<int>(r));
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  };

  if (scene.is_pattern()) {
    const GLuint p = pattern_progs_[mapping].id();
    glUseProgram(p);
    set_mapping(p, plan, texture_size);
    set(p, "u_viewport_size", glm::vec2(eye_w_, eye_h_));
    set(p, "u_angle", glm::radians(scene.pattern->angle_deg));
    set(p, "u_tile_px", scene.pattern->tile_px);
    // The tile's own (anisotropic) sampler: a pattern has no triangles, so the quad's
    // implicit derivatives are the footprint and llvmpipe's anisotropy sees it right.
    glBindTextureUnit(0, scene.pattern->texture.id());
    draw_regions(p);
    return;
  }

  const GLuint textures[2] = {visibility_->ids.id(), visibility_->depth.id()};
  glBindTextures(5, 2, textures);
  const SceneGeometry& geo = scene.geometry;
  const GLuint geometry[4] = {geo.vertex_pairs.id(), geo.triangles.id(), geo.draw_floats.id(), geo.draw_uints.id()};
  glBindTextures(8, 4, geometry);

  // Classification: each covered texel's material into the depth attachment.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_ALWAYS);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  const GLuint c = classify_progs_[mapping].id();
  glUseProgram(c);
  set_mapping(c, plan, texture_size);
  draw_regions(c);

  // Which materials each tile holds: per material a list of tiles and an indirect draw.
  const std::size_t slots = std::min(scene.materials.size() + 1, kMaterialSlots);
  MaterialTiles& tiles = dst.tiles;
  if (tiles.slots < slots) tiles = MaterialTiles::create(dst.width(), dst.height(), kMaterialTile, slots);
  glCopyNamedBufferSubData(tiles.empty.id(), tiles.commands.id(), 0, 0, static_cast<GLsizeiptr>(slots * 16));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, tiles.commands.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, tiles.lists.id());
  glBindTextureUnit(7, dst.material_depth.id());
  glUseProgram(tiles_prog_.id());
  set(tiles_prog_.id(), "u_list_capacity", static_cast<unsigned>(tiles.count()));
  glDispatchCompute(static_cast<GLuint>(tiles.across), static_cast<GLuint>(tiles.down), 1);
  glBindTextureUnit(7, 0);  // attached as depth below: not also bound for sampling
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);

  // One pass per material over its tiles, drawn at its depth: the EQUAL test runs the
  // material's shader only on its own texels, and early enough that the others in its
  // tiles cost no shading. The tiles are in the surface's texels: the viewport is the
  // whole surface and each region a scissor.
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_FALSE);
  glDepthFunc(GL_EQUAL);
  glViewport(0, 0, dst.width(), dst.height());
  glEnable(GL_SCISSOR_TEST);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, tiles.commands.id());
  const GLuint p = material_progs_[mapping].id();
  glUseProgram(p);
  set_mapping(p, plan, texture_size);
  set(p, "u_view_proj", view.view_proj);
  set(p, "u_tiles_across", static_cast<unsigned>(tiles.across));
  set(p, "u_surface_size", texture_size);
  for (std::size_t m : used_materials(scene)) {
    const Material& mat = material_of(scene, m < scene.materials.size() ? static_cast<int>(m) : -1);
    set_material(p, scene, mat);
    for (int slot = 0; slot < Material::slot_count; ++slot) {
      const int t = mat.texture(static_cast<Material::Slot>(slot));
      glBindSampler(material_texture_unit(slot), t >= 0 ? scene.isotropic_samplers[static_cast<std::size_t>(t)].id() : 0);
    }
    const std::size_t slot = std::min(m, kMaterialSlots - 1);
    set(p, "u_list_base", static_cast<unsigned>(slot * tiles.count()));
    const float z = material_depth(m);
    glDepthRangef(z, z);
    for (std::size_t r = 0; r < regions.size(); ++r) {
      glScissor(regions[r].x, regions[r].y, regions[r].z, regions[r].w);
      set(p, "u_layer", static_cast<int>(r));
      glDrawArraysIndirect(GL_TRIANGLES, reinterpret_cast<const void*>(slot * 16));
    }
  }
  glDisable(GL_SCISSOR_TEST);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  for (int slot = 0; slot < Material::slot_count; ++slot) glBindSampler(material_texture_unit(slot), 0);
  glBindTextures(8, 4, nullptr);
  glDepthRangef(0.0f, 1.0f);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glDisable(GL_DEPTH_TEST);
}

MaterialSurface& VisibilityPipeline::full_surface() { return ensure(full_, eye_w_, eye_h_, false, layout_); }

MaterialSurface& VisibilityPipeline::eye_surface(std::size_t eye, int w, int h, bool grow_only) {
  return ensure(eyes_[eye], w, h, grow_only, layout_);
}

std::size_t VisibilityPipeline::eye_surface_bytes() const {
  std::size_t b = 0;
  for (const auto& e : eyes_)
    if (e) b += e->bytes();
  return b;
}

}  // namespace foveal::render::detail

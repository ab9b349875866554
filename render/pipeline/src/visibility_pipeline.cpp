#include "visibility_pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include <glm/matrix.hpp>

#include "foveal/rmfr_mapping.hpp"
#include "foveal/render/scene.hpp"
#include "foveal/render/stereo_camera.hpp"
#include "pass_uniforms.hpp"

namespace foveal::render::detail {

namespace {

// The depth a material's texels carry between classification and its pass (as
// shaders/classify.frag writes it): exact in float for up to 2^20 materials.
constexpr float kMaterialDepthScale = 1.0f / 1048576.0f;

float material_depth(std::size_t material) { return static_cast<float>(material + 1) * kMaterialDepthScale; }

// Which material slots (Scene::materials, then the default) any draw uses.
std::vector<std::size_t> used_materials(const Scene& scene) {
  std::vector<bool> used(scene.materials.size() + 1, false);
  for (const DrawItem& d : scene.draws) {
    const int m = scene.primitives[static_cast<std::size_t>(d.primitive)].material;
    used[m >= 0 ? static_cast<std::size_t>(m) : scene.materials.size()] = true;
  }
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < used.size(); ++i)
    if (used[i]) out.push_back(i);
  return out;
}

const MaterialSurface& ensure(std::optional<MaterialSurface>& slot, int w, int h, bool grow_only) {
  if (auto size = realloc_size(slot.has_value(), slot ? slot->width() : 0, slot ? slot->height() : 0, w, h, grow_only))
    slot = MaterialSurface::create(size->first, size->second);
  return *slot;
}

// Where a material can be in the eye's buffer: the union over its draws of their bounds
// projected to the screen, mapped into the buffer. Only for the RMFR mapping (variant 0,
// full included), whose forward map is monotonic per axis so a screen rectangle maps onto
// a buffer rectangle; else, or when a draw reaches behind the eye, the whole buffer.
// x0, y0, x1, y1 in texels, with a margin.
struct TexelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

std::vector<std::optional<TexelRect>> material_rects(const Scene& scene, const glm::mat4& view_proj, const EyePlan& plan,
                                                     std::size_t mapping) {
  std::vector<std::optional<TexelRect>> rects(scene.materials.size() + 1);
  std::vector<bool> whole(rects.size(), mapping != 0);
  std::vector<glm::dvec4> screen(rects.size(), glm::dvec4(1, 1, 0, 0));  // normalised x0, y0, x1, y1
  for (const DrawItem& d : scene.draws) {
    const Primitive& p = scene.primitives[static_cast<std::size_t>(d.primitive)];
    const std::size_t m = p.material >= 0 ? static_cast<std::size_t>(p.material) : scene.materials.size();
    if (whole[m]) continue;
    const glm::mat4 to_clip = view_proj * d.world;
    for (int k = 0; k < 8; ++k) {
      const glm::vec3 c((k & 1) ? p.local_bounds.max.x : p.local_bounds.min.x, (k & 2) ? p.local_bounds.max.y : p.local_bounds.min.y,
                        (k & 4) ? p.local_bounds.max.z : p.local_bounds.min.z);
      const glm::vec4 q = to_clip * glm::vec4(c, 1.0f);
      if (!(q.w > 1e-6f)) {
        whole[m] = true;
        break;
      }
      const glm::dvec2 n = (glm::dvec2(q.x, q.y) / static_cast<double>(q.w) + 1.0) * 0.5;
      screen[m] = glm::dvec4(std::min(screen[m].x, n.x), std::min(screen[m].y, n.y), std::max(screen[m].z, n.x), std::max(screen[m].w, n.y));
    }
  }
  const bool full = plan.method == Method::full;
  const glm::dvec2 f = full ? glm::dvec2(rmfr::kRmfrIdentityF) : plan.f;
  const glm::dvec2 margin(1.0 / plan.screen_w, 1.0 / plan.screen_h);  // a pixel: the rasteriser's coverage
  for (std::size_t m = 0; m < rects.size(); ++m) {
    if (whole[m]) continue;
    if (screen[m].x > screen[m].z) {  // no draw
      rects[m] = TexelRect{};
      continue;
    }
    auto to_buffer = [&](double p, int axis, int size) {
      const double u = rmfr::rmfr_forward(std::clamp(p, 0.0, 1.0), plan.fovea[axis], f[axis]);
      return u * size;
    };
    TexelRect r;
    r.x0 = std::max(0, static_cast<int>(std::floor(to_buffer(screen[m].x - margin.x, 0, plan.buffer_w))) - 1);
    r.y0 = std::max(0, static_cast<int>(std::floor(to_buffer(screen[m].y - margin.y, 1, plan.buffer_h))) - 1);
    r.x1 = std::min(plan.buffer_w, static_cast<int>(std::ceil(to_buffer(screen[m].z + margin.x, 0, plan.buffer_w))) + 1);
    r.y1 = std::min(plan.buffer_h, static_cast<int>(std::ceil(to_buffer(screen[m].w + margin.y, 1, plan.buffer_h))) + 1);
    rects[m] = r;
  }
  return rects;
}

}  // namespace

Result<VisibilityPipeline> VisibilityPipeline::create(const gl::ShaderLoader& shaders, int eye_width, int eye_height) {
  VisibilityPipeline v;
  v.eye_w_ = eye_width;
  v.eye_h_ = eye_height;
  auto build = [&](gl::Program& out, std::vector<gl::ShaderStage> stages, const std::string& defines) -> Status {
    auto p = shaders.program(stages, defines);
    if (!p) return p.error();
    out = std::move(*p);
    return {};
  };
  const gl::ShaderStage geometry{GL_VERTEX_SHADER, "gbuffer.vert"}, visibility{GL_FRAGMENT_SHADER, "visibility.frag"};
  if (Status s = build(v.visibility_prog_, {geometry, visibility}, ""); !s) return s.error();
  if (Status s = build(v.visibility_mask_prog_, {geometry, visibility}, "#define ALPHA_MASK 1\n"); !s) return s.error();
  const gl::ShaderStage fullscreen{GL_VERTEX_SHADER, "fullscreen.vert"};
  for (std::size_t m = 0; m < 3; ++m) {
    const std::string mapping = "#define MAPPING " + std::to_string(m) + "\n";
    if (Status s = build(v.classify_progs_[m], {fullscreen, {GL_FRAGMENT_SHADER, "classify.frag"}}, mapping); !s) return s.error();
    if (Status s = build(v.material_progs_[m], {fullscreen, {GL_FRAGMENT_SHADER, "material.frag"}}, mapping); !s) return s.error();
    if (Status s = build(v.pattern_progs_[m], {fullscreen, {GL_FRAGMENT_SHADER, "material.frag"}}, mapping + "#define PATTERN 1\n"); !s)
      return s.error();
  }
  v.empty_vao_ = gl::VertexArray::create();
  return v;
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
                                       const std::vector<glm::ivec4>& regions, const MaterialSurface& dst) {
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
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, scene.geometry.draws.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, scene.geometry.vertices.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, scene.geometry.indices.id());

  // Classification: each covered texel's material into the depth attachment.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_ALWAYS);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  const GLuint c = classify_progs_[mapping].id();
  glUseProgram(c);
  set_mapping(c, plan, texture_size);
  draw_regions(c);

  // One pass per material, drawn at its depth: the EQUAL test runs the material's shader
  // only on its own texels, and early enough that the others cost no shading.
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_FALSE);
  glDepthFunc(GL_EQUAL);
  const GLuint p = material_progs_[mapping].id();
  glUseProgram(p);
  set_mapping(p, plan, texture_size);
  set(p, "u_view_proj", view.view_proj);
  const auto rects = material_rects(scene, view.view_proj, plan, mapping);
  for (std::size_t m : used_materials(scene)) {
    if (const auto& r = rects[m]) {  // only where the material can be
      if (r->x1 <= r->x0 || r->y1 <= r->y0) continue;
      glEnable(GL_SCISSOR_TEST);
      glScissor(r->x0, r->y0, r->x1 - r->x0, r->y1 - r->y0);
    }
    const Material& mat = material_of(scene, m < scene.materials.size() ? static_cast<int>(m) : -1);
    set_material(p, scene, mat);
    const int texs[] = {mat.base_color_tex, mat.metal_rough_tex, mat.normal_tex, mat.occlusion_tex, mat.emissive_tex};
    for (GLuint unit = 0; unit < 5; ++unit)
      glBindSampler(unit, texs[unit] >= 0 ? scene.isotropic_samplers[static_cast<std::size_t>(texs[unit])].id() : 0);
    const float z = material_depth(m);
    glDepthRangef(z, z);
    draw_regions(p);
    glDisable(GL_SCISSOR_TEST);
  }
  glBindSamplers(0, 5, nullptr);
  glDepthRangef(0.0f, 1.0f);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glDisable(GL_DEPTH_TEST);
}

const MaterialSurface& VisibilityPipeline::full_surface() { return ensure(full_, eye_w_, eye_h_, false); }

const MaterialSurface& VisibilityPipeline::eye_surface(std::size_t eye, int w, int h, bool grow_only) {
  return ensure(eyes_[eye], w, h, grow_only);
}

std::size_t VisibilityPipeline::eye_surface_bytes() const {
  std::size_t b = 0;
  for (const auto& e : eyes_)
    if (e) b += e->bytes();
  return b;
}

}  // namespace foveal::render::detail

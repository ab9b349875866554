#include "foveal/render/compositor.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>

#include <glm/gtc/type_ptr.hpp>

#include "foveal/image/method_description.hpp"
#include "foveal/rmfr_mapping.hpp"
#include "foveal/render/light_rig.hpp"
#include "foveal/render/light_tiles.hpp"
#include "foveal/render/scene.hpp"
#include "foveal/render/stereo_camera.hpp"
#include "foveal/rmfr.hpp"
#include "pass_uniforms.hpp"
#include "render_targets.hpp"
#include "sheen_albedo.hpp"
#include "visibility_pipeline.hpp"

namespace foveal::render {

FrameParams efr_frame(Method method, Eye dominant, double sigma_d, double sigma_nd, double fx, double fy) {
  FrameParams p;
  p.method = method;
  for (Eye e : kEyes) {
    EyeFoveation& f = p.eyes[static_cast<std::size_t>(e)];
    f.sigma = e == dominant ? sigma_d : sigma_nd;
    f.fx = fx;
    f.fy = fy;
  }
  return p;
}

namespace {

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

const std::vector<Pipeline>& all_pipelines() {
  static const std::vector<Pipeline> p = {Pipeline::gbuffer, Pipeline::visibility};
  return p;
}

const char* pipeline_name(Pipeline p) { return p == Pipeline::visibility ? "visibility" : "gbuffer"; }

const std::vector<std::string>& pipeline_names() {
  static const std::vector<std::string> n = {"gbuffer", "visibility"};
  return n;
}

Result<Pipeline> parse_pipeline(const std::string& s) {
  for (Pipeline p : all_pipelines())
    if (s == pipeline_name(p)) return p;
  return bad_input("unknown pipeline '" + s + "' (gbuffer, visibility)");
}

std::array<const char*, 2> pass_names(Pipeline p) {
  if (p == Pipeline::visibility) return {"visibility", "material"};
  return {"gbuffer", "mapping"};
}

PassTimes median_pass_times(const std::vector<PassTimes>& frames) {
  PassTimes m;
  if (frames.empty()) return m;
  auto median = [&](double PassTimes::*field) {
    std::vector<double> v;
    for (const PassTimes& t : frames) v.push_back(t.*field);
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  };
  for (double PassTimes::*f : {&PassTimes::shadow, &PassTimes::gbuffer, &PassTimes::mapping, &PassTimes::lighting,
                               &PassTimes::inverse, &PassTimes::blend, &PassTimes::gpu_total, &PassTimes::cpu})
    m.*f = median(f);
  m.shaded_samples = frames.back().shaded_samples;
  m.pipeline = frames.back().pipeline;
  return m;
}

namespace {

using Clock = std::chrono::steady_clock;

using detail::set;

// Which pass a GPU timestamp interval belongs to.
enum class Pass { shadow, gbuffer, mapping, lighting, inverse, blend };

// GL_TIMESTAMP queries at pass boundaries, read back once the frame is finished.
class PassTimer {
 public:
  void begin_frame() { count_ = 0; }
  void mark(Pass finished) {
    if (count_ >= queries_.size()) {
      GLuint id = 0;
      glCreateQueries(GL_TIMESTAMP, 1, &id);
      queries_.emplace_back(id);
      passes_.push_back(finished);
    }
    passes_[count_] = finished;
    glQueryCounter(queries_[count_++].id(), GL_TIMESTAMP);
  }
  // Call after glFinish. Interval i (mark i-1 -> mark i) is charged to passes_[i].
  void collect(PassTimes& t) const {
    std::vector<GLuint64> stamp(count_);
    for (std::size_t i = 0; i < count_; ++i) glGetQueryObjectui64v(queries_[i].id(), GL_QUERY_RESULT, &stamp[i]);
    for (std::size_t i = 1; i < count_; ++i) {
      const double ms = static_cast<double>(stamp[i] - stamp[i - 1]) / 1e6;
      switch (passes_[i]) {
        case Pass::shadow: t.shadow += ms; break;
        case Pass::gbuffer: t.gbuffer += ms; break;
        case Pass::mapping: t.mapping += ms; break;
        case Pass::lighting: t.lighting += ms; break;
        case Pass::inverse: t.inverse += ms; break;
        case Pass::blend: t.blend += ms; break;
      }
    }
    if (count_ > 1) t.gpu_total = static_cast<double>(stamp[count_ - 1] - stamp[0]) / 1e6;
  }

 private:
  std::vector<gl::Query> queries_;
  std::vector<Pass> passes_;
  std::size_t count_ = 0;
};

}  // namespace

std::size_t mapping_variant_count() { return kBuiltinMappings + described_kernels().size(); }

std::string mapping_define(std::size_t v) {
  return "#define MAPPING " + std::to_string(std::min(v, kBuiltinMappings)) + "\n";
}

std::vector<gl::VirtualFile> mapping_files(std::size_t v) {
  if (v < kBuiltinMappings || v >= mapping_variant_count()) return {};
  return {{"method/kernel", described_kernels()[v - kBuiltinMappings]->kernel_glsl}};
}

namespace detail {

const Material& material_of(const Scene& scene, int material) {
  static const Material kDefault{};
  return material >= 0 ? scene.materials[static_cast<std::size_t>(material)] : kDefault;
}

bool has_forward_draws(const Scene& scene) {
  for (const DrawItem& d : scene.draws)
    if (material_of(scene, scene.primitives[static_cast<std::size_t>(d.primitive)].material).forward()) return true;
  return false;
}

void set_material(GLuint p, const Scene& scene, const Material& m) {
  set(p, "u_base_color", m.base_color);
  set(p, "u_emissive", m.emissive);
  set(p, "u_metallic", m.metallic);
  set(p, "u_roughness", m.roughness);
  set(p, "u_normal_scale", m.normal_scale);
  set(p, "u_occlusion_strength", m.occlusion_strength);
  set(p, "u_alpha_cutoff", m.alpha_cutoff);
  set(p, "u_unlit", m.unlit ? 1 : 0);
  set(p, "u_double_sided", m.double_sided ? 1 : 0);
  set(p, "u_has_tex", glm::ivec4(m.base_color_tex >= 0, m.metal_rough_tex >= 0, m.normal_tex >= 0, m.occlusion_tex >= 0));
  set(p, "u_has_emissive_tex", m.emissive_tex >= 0 ? 1 : 0);
  // Per-slot texture coordinates and KHR_texture_transform matrices, the spec-gloss factors.
  std::array<glm::mat3, Material::slot_count> matrices;
  std::array<GLint, Material::slot_count> sets;
  for (std::size_t i = 0; i < m.uv.size(); ++i) matrices[i] = m.uv[i].matrix, sets[i] = m.uv[i].set;
  glProgramUniformMatrix3fv(p, loc(p, "u_uv_matrix"), Material::slot_count, GL_FALSE, glm::value_ptr(matrices[0]));
  glProgramUniform1iv(p, loc(p, "u_uv_set"), Material::slot_count, sets.data());
  set(p, "u_spec_gloss", m.spec_gloss ? 1 : 0);
  set(p, "u_specular", m.specular);
  set(p, "u_glossiness", m.glossiness);
  // The extensions' (material.glsl, FEATURE_*).
  int ext = 0;
  for (std::size_t i = 0; i < m.ext_tex.size(); ++i)
    if (m.ext_tex[i] >= 0) ext |= 1 << i;
  set(p, "u_ext_tex", ext);
  set(p, "u_clearcoat", glm::vec3(m.features & feature_clearcoat ? m.clearcoat : 0.0f, m.clearcoat_roughness, m.clearcoat_normal_scale));
  set(p, "u_sheen", glm::vec4(m.features & feature_sheen ? m.sheen_color : glm::vec3(0.0f), m.sheen_roughness));
  set(p, "u_specular_layer", glm::vec4(m.specular_color, m.specular_factor));
  set(p, "u_ior", m.ior);
  set(p, "u_blend", m.blend ? 1 : 0);
  set(p, "u_transmission", glm::vec4(m.features & feature_transmission ? m.transmission : 0.0f, m.thickness, m.attenuation_distance, 0.0f));
  set(p, "u_attenuation_color", m.attenuation_color);
  set(p, "u_anisotropy", glm::vec2(m.features & feature_anisotropy ? m.anisotropy : 0.0f, m.anisotropy_rotation));
  set(p, "u_iridescence", glm::vec4(m.features & feature_iridescence ? m.iridescence : 0.0f, m.iridescence_ior,
                                    m.iridescence_thickness_min, m.iridescence_thickness_max));
  const bool any_ext = ext != 0;
  for (int slot = 0; slot < (any_ext ? Material::slot_count : Material::kCoreSlots); ++slot) {
    const int t = m.texture(static_cast<Material::Slot>(slot));
    glBindTextureUnit(material_texture_unit(slot), t >= 0 ? scene.textures[static_cast<std::size_t>(t)].id() : 0);
  }
}

}  // namespace detail

Result<std::size_t> mapping_index(const EyePlan& plan) {
  if (const int k = kernel_index(plan.method); k >= 0) return kBuiltinMappings + static_cast<std::size_t>(k);
  switch (plan.method) {
    case Method::full:
    case Method::rmfr:
    case Method::uniform:
    case Method::fixed: return std::size_t{0};
    case Method::kfr: return std::size_t{1};
    case Method::hyperbolic:
    case Method::linear: return std::size_t{2};
  }
  return bad_input("no mapping for foveation method " + std::to_string(static_cast<int>(plan.method)));
}

// An RMFR eye's plan as foveal-rmfr takes it (plan_eye computed it with the library's
// formulas, foveal/rmfr_mapping.hpp).
rmfr::Plan rmfr_plan(const EyePlan& p) {
  rmfr::Plan r;
  r.screen_w = p.screen_w, r.screen_h = p.screen_h;
  r.buffer_w = p.buffer_w, r.buffer_h = p.buffer_h;
  r.sigma = static_cast<double>(p.screen_w) / p.buffer_w;  // informative; the passes use the sizes
  r.fovea_x = p.fovea.x, r.fovea_y = p.fovea.y;
  r.fx = p.f.x, r.fy = p.f.y;
  r.frustum = {p.frustum.tan_left, p.frustum.tan_right, p.frustum.tan_bottom, p.frustum.tan_top};
  return r;
}

rmfr::Lens rmfr_lens(const LensDistortion& l) {
  return {l.center.x, l.center.y, l.k1, l.k2, l.k3, {l.channel_scale.x, l.channel_scale.y, l.channel_scale.z}};
}

// The mapping uniforms of shaders/common/mapping.glsl for one eye's plan.
void set_mapping(GLuint p, const EyePlan& plan, glm::vec2 texture_size) {
  const bool full = plan.method == Method::full;
  set(p, "u_buffer_size", glm::vec2(plan.buffer_w, plan.buffer_h));
  set(p, "u_texture_size", texture_size);
  set(p, "u_screen_size", glm::vec2(plan.screen_w, plan.screen_h));
  set(p, "u_fovea", glm::vec2(plan.fovea));
  const float identity = static_cast<float>(rmfr::kRmfrIdentityF);
  set(p, "u_f", full ? glm::vec2(identity) : glm::vec2(plan.f));
  set(p, "u_kfr", glm::vec2(static_cast<float>(plan.kfr_log_max), static_cast<float>(plan.kfr_alpha)));
  set(p, "u_tan", glm::vec4(plan.frustum.tan_left, plan.frustum.tan_right, plan.frustum.tan_bottom, plan.frustum.tan_top));
  const int n = std::min<int>(static_cast<int>(plan.layers.size()), 8);
  set(p, "u_layer_count", n);
  for (int i = 0; i < n; ++i) {
    const Layer& l = plan.layers[static_cast<std::size_t>(i)];
    const std::string k = "[" + std::to_string(i) + "]";
    set(p, ("u_layer_rect" + k).c_str(), glm::vec4(l.x, l.y, l.w, l.h));
    set(p, ("u_layer_atlas" + k).c_str(), glm::vec4(l.atlas_y, l.buffer_w, l.buffer_h, l.pixel_size));
    set(p, ("u_layer_ecc" + k).c_str(), std::isfinite(l.ecc_max_deg) ? static_cast<float>(l.ecc_max_deg) : 1e9f);
  }
  set(p, "u_layer", 0);
  set(p, "u_kernel_params", glm::vec4(plan.kernel_params));
}

struct Compositor::Impl {
  CompositorOptions opt;
  int eye_w = 0, eye_h = 0;
  gl::Program gbuffer_prog, pattern_prog, shadow_prog, blend_prog;
  // One per MAPPING variant (mapping_variant_count: 0 RMFR/full, 1 KFR, 2 layers, then
  // the described methods' kernels, built on first use); resolve also with and without
  // the lens. RMFR maps and resolves through foveal-rmfr, so its map and resolve slots stay empty.
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
  detail::ColorTarget output, shadow;
  std::array<EyePlan, 2> plans{};
  PassTimer timer;

  GLenum reduced_format() const { return opt.float_output ? GL_RGBA32F : GL_SRGB8_ALPHA8; }

  void draw_geometry(const Scene& scene, const EyeView& v) {
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

  void draw_pattern(const Scene& scene) {
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

  void shadow_pass(const Scene& scene) {
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

  Status build(gl::Program& out, const std::vector<gl::ShaderStage>& stages, const std::string& defines,
               const std::vector<gl::VirtualFile>& files = {}) const {
    auto p = shaders.program(stages, defines, files);
    if (!p) return p.error();
    out = std::move(*p);
    return {};
  }

  // The shader variant and G-buffer layout for material features `features`, and the
  // lighting and blend programs for the scene's lights: the file's (FILE_LIGHTS) or the
  // rig's. Code a scene does not use is not compiled in: on llvmpipe even a light loop
  // that never runs cost the rig-lit Dungeon 6% of its lighting pass.
  Status use_features(unsigned features, bool file_lights) {
    const bool same_features = features == requested_features && gbuffer_prog;
    if (same_features && file_lights == requested_file_lights && lighting_progs[0]) return {};
    const detail::SurfaceLayout next = same_features ? layout : detail::SurfaceLayout::for_features(features);
    if (!same_features && features) {
      GLint units = 0, buffers = 0;
      glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &units);
      glGetIntegerv(GL_MAX_DRAW_BUFFERS, &buffers);
      const GLint need_units = static_cast<GLint>(detail::material_texture_unit(Material::slot_count - 1)) + 1;
      const GLint need_buffers = static_cast<GLint>(detail::SurfaceLayout::kFirstLocation + next.targets.size());
      if (units < need_units || buffers < need_buffers)
        return Error{ErrorKind::unsupported, "the material variant " + next.variant_name() + " needs " + std::to_string(need_units) +
                                                 " fragment texture units and " + std::to_string(need_buffers) +
                                                 " draw buffers; this GL has " + std::to_string(units) + " and " + std::to_string(buffers)};
    }
    // A features change that fails part way leaves no G-buffer program, so the next frame
    // builds every program again rather than keep lighting built for a layout not in use.
    if (!same_features) gbuffer_prog.reset();
    const std::string d = next.defines();
    const std::string lit = d + (file_lights ? "#define FILE_LIGHTS 1\n" : "");
    if (Status s = build(blend_prog, {{GL_VERTEX_SHADER, "gbuffer.vert"}, {GL_FRAGMENT_SHADER, "blend.frag"}}, lit); !s) return s;
    const gl::ShaderStage vert{GL_VERTEX_SHADER, "fullscreen.vert"};
    for (std::size_t m = 0; m < kBuiltinMappings; ++m)
      if (Status s = build(lighting_progs[m], {vert, {GL_FRAGMENT_SHADER, "lighting.frag"}}, mapping_define(m) + lit); !s) return s;
    for (std::size_t m = kBuiltinMappings; m < lighting_progs.size(); ++m) lighting_progs[m].reset();  // rebuilt on use
    lit_defines = lit;
    requested_file_lights = file_lights;
    if (same_features) return {};  // the rest depends on the features only
    if (Status s = build(gbuffer_prog, {{GL_VERTEX_SHADER, "gbuffer.vert"}, {GL_FRAGMENT_SHADER, "gbuffer.frag"}}, d); !s) return s;
    for (std::size_t m = 1; m < kBuiltinMappings; ++m)  // RMFR maps through foveal-rmfr, which maps every attachment
      if (Status s = build(map_progs[m], {vert, {GL_FRAGMENT_SHADER, "map.frag"}}, mapping_define(m) + d); !s) return s;
    for (std::size_t m = kBuiltinMappings; m < map_progs.size(); ++m) map_progs[m].reset();
    if (Status s = visibility->use_layout(shaders, next); !s) return s;
    if ((features & feature_sheen) && !sheen_albedo) {
      constexpr int kSize = 32;
      const std::vector<float> table = detail::sheen_albedo_table(kSize);
      sheen_albedo = gl::make_texture_2d(GL_R32F, kSize, kSize);
      glTextureSubImage2D(sheen_albedo.id(), 0, 0, 0, kSize, kSize, GL_RED, GL_FLOAT, table.data());
      glTextureParameteri(sheen_albedo.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTextureParameteri(sheen_albedo.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTextureParameteri(sheen_albedo.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glTextureParameteri(sheen_albedo.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    layout = next;
    requested_features = features;
    gbuffer.reset();
    for (auto& t : transformed) t.reset();
    return {};
  }

  // A described method's programs (variant v >= kBuiltinMappings), built on first use
  // and again after a features change: compiling every kernel up front would cost each
  // compositor the programs of methods it never runs.
  Status ensure_variant(std::size_t v) {
    if (v < kBuiltinMappings) return {};
    const std::vector<gl::VirtualFile> files = mapping_files(v);
    const gl::ShaderStage vert{GL_VERTEX_SHADER, "fullscreen.vert"};
    if (!lighting_progs[v])
      if (Status s = build(lighting_progs[v], {vert, {GL_FRAGMENT_SHADER, "lighting.frag"}}, mapping_define(v) + lit_defines, files); !s)
        return s;
    if (!map_progs[v])
      if (Status s = build(map_progs[v], {vert, {GL_FRAGMENT_SHADER, "map.frag"}}, mapping_define(v) + layout.defines(), files); !s)
        return s;
    for (std::size_t lens = 0; lens < 2; ++lens)
      if (!resolve_progs[v][lens])
        if (Status s = build(resolve_progs[v][lens], {vert, {GL_FRAGMENT_SHADER, "resolve.frag"}},
                             mapping_define(v) + (lens ? "#define DISTORTION 1\n" : ""), files);
            !s)
          return s;
    return visibility->ensure_mapping(shaders, v);
  }

  // Lighting from `src` (G-buffer or reduced buffer) into the bound framebuffer, with
  // the mapping uniforms already set on the program.
  void lighting_pass(GLuint p, const detail::SurfaceTargets& src, glm::ivec2 origin, const EyeView& v) {
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

  // alphaMode BLEND, after the eye's lit opaque result is complete in the output: each
  // blended draw shaded forward at output resolution, back to front by the distance of
  // its bounds' centre from the eye, composited "over" it (straight alpha), tested
  // against the eye's opaque depth `depth` (W×H) without writing depth, into the eye's
  // viewport at `origin` of `fbo`.
  // Transmission shows the opaque result behind: a mipmapped copy of the eye's region of
  // `color` at `origin` (the roughness blurs by level).
  void copy_behind(GLuint color, glm::ivec2 origin) {
    if (!behind) {
      const int levels = 1 + static_cast<int>(std::floor(std::log2(static_cast<double>(std::max(eye_w, eye_h)))));
      detail::ColorTarget t;
      t.width = eye_w, t.height = eye_h;
      t.bytes_per_pixel = opt.float_output ? 16 : 4;
      t.texture = gl::make_texture_2d(reduced_format(), eye_w, eye_h, levels);
      glTextureParameteri(t.texture.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
      glTextureParameteri(t.texture.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTextureParameteri(t.texture.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glTextureParameteri(t.texture.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
      behind = std::move(t);
    }
    glCopyImageSubData(color, GL_TEXTURE_2D, 0, origin.x, origin.y, 0, behind->texture.id(), GL_TEXTURE_2D, 0, 0, 0, 0, eye_w, eye_h, 1);
    glGenerateTextureMipmap(behind->texture.id());
  }

  void blend_pass(const Scene& scene, const EyeView& v, GLuint fbo, GLuint color, glm::ivec2 origin, GLuint depth) {
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
      // Single-sided: back faces culled, as glTF says; a mirroring transform flips the winding.
      if (mat.double_sided) {
        glDisable(GL_CULL_FACE);
      } else {
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        glFrontFace(glm::determinant(glm::mat3(d.world)) < 0.0f ? GL_CW : GL_CCW);
      }
      glBindVertexArray(prim.vao.id());
      glDrawElements(GL_TRIANGLES, prim.index_count, GL_UNSIGNED_INT, nullptr);
    }
    glDisable(GL_CULL_FACE);
    glFrontFace(GL_CCW);
    glDisable(GL_BLEND);
  }

  // The depth texture of the eye just drawn: the G-buffer's or the visibility target's.
  GLuint opaque_depth(Pipeline pipeline) const {
    return pipeline == Pipeline::visibility ? visibility->depth_texture() : gbuffer->depth.id();
  }

  // Exact size for single-buffer methods; the layered methods' atlas changes shape with
  // the fovea every frame, so it only grows.
  void ensure_transformed(std::size_t eye, int w, int h, bool grow_only) {
    const auto& t = transformed[eye];
    if (auto size = detail::realloc_size(t.has_value(), t ? t->width : 0, t ? t->height : 0, w, h, grow_only))
      transformed[eye] = detail::SurfaceTargets::create(size->first, size->second, true, layout);
  }
  void ensure_undistorted() {
    if (!undistorted) undistorted = detail::ColorTarget::create(eye_w, eye_h, reduced_format(), true);
  }
  void ensure_reduced(std::size_t eye, int w, int h, bool grow_only) {
    const auto& r = reduced[eye];
    if (auto size = detail::realloc_size(r.has_value(), r ? r->width : 0, r ? r->height : 0, w, h, grow_only))
      reduced[eye] = detail::ColorTarget::create(size->first, size->second, reduced_format(), true);
  }

  Result<const detail::SurfaceTargets*> gbuffer_targets() {
    if (!gbuffer) {
      gbuffer = detail::SurfaceTargets::create(eye_w, eye_h, false, layout);
      if (glCheckNamedFramebufferStatus(gbuffer->fbo.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return Error{ErrorKind::unsupported, "the G-buffer framebuffer is incomplete on this GL implementation"};
    }
    return &*gbuffer;
  }

  // An eye's full-resolution pass, the first of its surface and the last that does not
  // depend on the fovea: the G-buffer, or the visibility pass.
  Status full_resolution_pass(const Scene& scene, const EyeView& view, Pipeline pipeline) {
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
  Result<const detail::SurfaceTargets*> gbuffer_surface(const EyePlan& plan, std::size_t eye, std::size_t variant,
                                                       const std::vector<glm::ivec4>& regions) {
    auto g = gbuffer_targets();
    if (!g) return g.error();
    if (plan.method == Method::full) return *g;

    // Mapping: G-buffer -> reduced G-buffer; RMFR's (also full through the lens) is foveal-rmfr's.
    ensure_transformed(eye, plan.buffer_w, plan.buffer_h, !plan.layers.empty());
    const detail::SurfaceTargets& tg = *transformed[eye];
    if (variant == 0) {  // RMFR's kernel: rmfr, and uniform and fixed as plans on it
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
  const detail::SurfaceTargets* visibility_surface(const Scene& scene, const EyeView& view, const EyePlan& plan,
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
  void run_latch(const FoveaLatch& latch, std::array<EyeFoveation, 2>& eyes, PassTimes& times) {
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
};

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
  for (std::size_t m = 1; m < kBuiltinMappings; ++m) {  // RMFR's resolve is foveal-rmfr's
    const std::string mapping = "#define MAPPING " + std::to_string(m) + "\n";
    for (std::size_t lens = 0; lens < 2; ++lens)
      if (Status s = impl->build(impl->resolve_progs[m][lens], {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "resolve.frag"}},
                                 mapping + (lens ? "#define DISTORTION 1\n" : ""));
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
    const bool blend_under_lens = distort && blended;
    if (blend_under_lens) m.ensure_undistorted();
    const GLuint resolve_fbo = blend_under_lens ? m.undistorted->fbo.id() : m.output.fbo.id();
    const glm::ivec2 resolve_origin = blend_under_lens ? glm::ivec2(0) : eye_origin;
    auto blend_eye = [&]() -> Status {
      if (!blended) return {};
      // llvmpipe runs the draws into one target as one scene, tile by tile, and stamps a
      // pass's end when its last tile is done: without a flush the previous pass's stamp
      // would fall after most of this pass (measured: the blend pass read 0 ms in full).
      glFlush();
      m.blend_pass(scene, view, resolve_fbo, blend_under_lens ? m.undistorted->texture.id() : m.output.texture.id(), resolve_origin,
                   m.opaque_depth(params.pipeline));
      if (blend_under_lens) {
        rmfr::Plan identity = rmfr_plan(plan);
        identity.buffer_w = identity.screen_w, identity.buffer_h = identity.screen_h;
        identity.sigma = 1.0;
        identity.fx = identity.fy = rmfr::kRmfrIdentityF;
        const rmfr::Lens l = rmfr_lens(lens);
        if (Status s = m.foveator->resolve(identity, m.undistorted->texture.id(), m.output.fbo.id(), eye_origin.x,
                                           eye_origin.y, &l);
            !s)
          return s;
      }
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

    // Resolve into this eye's half of the output. KFR's angle axis wraps around.
    if (variant == 0) {  // RMFR's kernel (rmfr, uniform, fixed): foveal-rmfr's resolve
      const rmfr::Lens l = rmfr_lens(lens);
      if (Status s = m.foveator->resolve(rmfr_plan(plan), rs.texture.id(), resolve_fbo, resolve_origin.x,
                                         resolve_origin.y, distort && !blend_under_lens ? &l : nullptr);
          !s)
        return s.error();
      m.timer.mark(Pass::inverse);
      if (Status s = blend_eye(); !s) return s.error();
      continue;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, resolve_fbo);
    glViewport(resolve_origin.x, resolve_origin.y, m.eye_w, m.eye_h);
    glTextureParameteri(rs.texture.id(), GL_TEXTURE_WRAP_T, plan.method == Method::kfr ? GL_REPEAT : GL_CLAMP_TO_EDGE);
    const GLuint ip = m.resolve_progs[variant][distort && !blend_under_lens ? 1 : 0].id();
    glUseProgram(ip);
    set_mapping(ip, plan, texture_size);
    set(ip, "u_origin", resolve_origin);
    set(ip, "u_lens_center", glm::vec2(lens.center.x, 1.0f - lens.center.y));
    set(ip, "u_lens_k", glm::vec3(lens.k1, lens.k2, lens.k3));
    set(ip, "u_lens_scale", lens.channel_scale);
    glBindTextureUnit(0, rs.texture.id());
    glBindVertexArray(m.empty_vao.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    m.timer.mark(Pass::inverse);
    if (Status s = blend_eye(); !s) return s.error();
  }
  glFinish();
  times.gpu_done_ns = monotonic_now_ns();
  times.cpu = std::chrono::duration<double, std::milli>(Clock::now() - cpu_start).count();
  m.timer.collect(times);
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

TargetMemory Compositor::memory() const {
  TargetMemory t = memory(Pipeline::gbuffer);
  const TargetMemory v = memory(Pipeline::visibility);
  t.gbuffer += v.gbuffer;
  t.transformed += v.transformed;
  t.visibility = v.visibility;
  return t;
}

TargetMemory Compositor::memory(Pipeline p) const {
  const Impl& m = *impl_;
  TargetMemory t;
  for (std::size_t i = 0; i < 2; ++i)
    if (m.reduced[i]) t.reduced += m.reduced[i]->bytes();
  // The blend target under the lens, and the copy transmission reads (its mips: a third more).
  t.output = m.output.bytes() + (m.undistorted ? m.undistorted->bytes() : 0) + (m.behind ? m.behind->bytes() * 4 / 3 : 0);
  t.shadow = m.shadow.bytes();
  if (p == Pipeline::visibility) {
    t.visibility = m.visibility->visibility_bytes();
    t.transformed = m.visibility->eye_surface_bytes();
    t.gbuffer = m.visibility->full_surface_bytes();
    return t;
  }
  t.gbuffer = m.gbuffer ? m.gbuffer->bytes() : 0;
  for (std::size_t i = 0; i < 2; ++i)
    if (m.transformed[i]) t.transformed += m.transformed[i]->bytes();
  return t;
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

#include "foveal/render/compositor.hpp"

#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>

#include <glm/gtc/type_ptr.hpp>

#include "foveal/image/rmfr_mapping.hpp"
#include "foveal/render/light_rig.hpp"
#include "foveal/render/scene.hpp"
#include "foveal/render/stereo_camera.hpp"
#include "render_targets.hpp"

namespace foveal::render {

const char* method_name(Method m) { return m == Method::full ? "full" : "rmfr"; }

Result<Method> parse_method(const std::string& s) {
  if (s == "full") return Method::full;
  if (s == "rmfr") return Method::rmfr;
  return bad_input("unknown method '" + s + "' (full, rmfr)");
}

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

using Clock = std::chrono::steady_clock;

GLint loc(GLuint program, const char* name) { return glGetUniformLocation(program, name); }
void set(GLuint p, const char* n, int v) { glProgramUniform1i(p, loc(p, n), v); }
void set(GLuint p, const char* n, float v) { glProgramUniform1f(p, loc(p, n), v); }
void set(GLuint p, const char* n, glm::vec2 v) { glProgramUniform2f(p, loc(p, n), v.x, v.y); }
void set(GLuint p, const char* n, glm::ivec2 v) { glProgramUniform2i(p, loc(p, n), v.x, v.y); }
void set(GLuint p, const char* n, glm::vec3 v) { glProgramUniform3f(p, loc(p, n), v.x, v.y, v.z); }
void set(GLuint p, const char* n, glm::vec4 v) { glProgramUniform4f(p, loc(p, n), v.x, v.y, v.z, v.w); }
void set(GLuint p, const char* n, glm::ivec4 v) { glProgramUniform4i(p, loc(p, n), v.x, v.y, v.z, v.w); }
void set(GLuint p, const char* n, const glm::mat3& m) { glProgramUniformMatrix3fv(p, loc(p, n), 1, GL_FALSE, glm::value_ptr(m)); }
void set(GLuint p, const char* n, const glm::mat4& m) { glProgramUniformMatrix4fv(p, loc(p, n), 1, GL_FALSE, glm::value_ptr(m)); }

// Which pass a GPU timestamp interval belongs to.
enum class Pass { shadow, gbuffer, mapping, lighting, inverse };

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

struct Compositor::Impl {
  CompositorOptions opt;
  int eye_w = 0, eye_h = 0;
  gl::Program gbuffer_prog, pattern_prog, shadow_prog, map_prog, lighting_prog, inverse_prog;
  gl::VertexArray empty_vao;
  gl::Buffer lights_ubo;
  detail::SurfaceTargets gbuffer;
  std::array<std::optional<detail::SurfaceTargets>, 2> transformed;
  std::array<std::optional<detail::ColorTarget>, 2> reduced;
  detail::ColorTarget output, shadow;
  std::array<std::array<int, 2>, 2> last_size{};
  bool shadow_used = false;
  PassTimer timer;

  GLenum reduced_format() const { return opt.float_output ? GL_RGBA32F : GL_SRGB8_ALPHA8; }

  void draw_geometry(const Scene& scene, const EyeView& v) {
    const GLuint p = gbuffer_prog.id();
    glUseProgram(p);
    set(p, "u_view_proj", v.view_proj);
    for (const DrawItem& d : scene.draws) {
      const Primitive& prim = scene.primitives[static_cast<std::size_t>(d.primitive)];
      static const Material kDefault{};
      const Material& m = prim.material >= 0 ? scene.materials[static_cast<std::size_t>(prim.material)] : kDefault;
      set(p, "u_model", d.world);
      set(p, "u_normal_matrix", glm::mat3(glm::transpose(glm::inverse(d.world))));
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
      const int texs[] = {m.base_color_tex, m.metal_rough_tex, m.normal_tex, m.occlusion_tex, m.emissive_tex};
      for (GLuint unit = 0; unit < 5; ++unit)
        glBindTextureUnit(unit, texs[unit] >= 0 ? scene.textures[static_cast<std::size_t>(texs[unit])].id() : 0);
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
      set(p, "u_model", d.world);
      glBindVertexArray(prim.vao.id());
      glDrawElements(GL_TRIANGLES, prim.index_count, GL_UNSIGNED_INT, nullptr);
    }
  }

  // Lighting from `src` (G-buffer or transformed buffer) into the bound framebuffer.
  void lighting_pass(const detail::SurfaceTargets& src, glm::ivec2 origin, glm::vec2 fovea, glm::vec2 f, const EyeView& v) {
    const GLuint p = lighting_prog.id();
    glUseProgram(p);
    set(p, "u_origin", origin);
    set(p, "u_buffer_size", glm::vec2(src.width, src.height));
    set(p, "u_screen_size", glm::vec2(eye_w, eye_h));
    set(p, "u_fovea", fovea);
    set(p, "u_f", f);
    set(p, "u_inv_view_proj", v.inv_view_proj);
    set(p, "u_camera_pos", v.position);
    src.bind_textures();
    glBindTextureUnit(5, shadow.texture.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, lights_ubo.id());
    glBindVertexArray(empty_vao.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }

  Status ensure_eye_buffers(std::size_t eye, int w, int h) {
    if (!transformed[eye] || transformed[eye]->width != w || transformed[eye]->height != h) {
      transformed[eye] = detail::SurfaceTargets::create(w, h, true);
      reduced[eye] = detail::ColorTarget::create(w, h, reduced_format(), true);
    }
    return {};
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
  auto build = [&](gl::Program& out, std::vector<gl::ShaderStage> stages) -> Status {
    auto p = shaders.program(stages);
    if (!p) return p.error();
    out = std::move(*p);
    return {};
  };
  const std::vector<std::pair<gl::Program*, std::vector<gl::ShaderStage>>> programs = {
      {&impl->gbuffer_prog, {{GL_VERTEX_SHADER, "gbuffer.vert"}, {GL_FRAGMENT_SHADER, "gbuffer.frag"}}},
      {&impl->pattern_prog, {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "pattern.frag"}}},
      {&impl->shadow_prog, {{GL_VERTEX_SHADER, "shadow.vert"}}},
      {&impl->map_prog, {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "rmfr_map.frag"}}},
      {&impl->lighting_prog, {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "lighting.frag"}}},
      {&impl->inverse_prog, {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "rmfr_inverse.frag"}}},
  };
  for (const auto& [prog, stages] : programs)
    if (Status s = build(*prog, stages); !s) return s.error();

  impl->empty_vao = gl::VertexArray::create();
  impl->lights_ubo = gl::Buffer::create();
  glNamedBufferStorage(impl->lights_ubo.id(), sizeof(LightBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
  impl->gbuffer = detail::SurfaceTargets::create(impl->eye_w, impl->eye_h, false);
  impl->output = detail::ColorTarget::create(o.width, o.height, o.float_output ? GL_RGBA32F : GL_SRGB8_ALPHA8, false);
  impl->shadow = detail::ColorTarget::create_shadow(o.shadow_map_size);
  if (glCheckNamedFramebufferStatus(impl->gbuffer.fbo.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE ||
      glCheckNamedFramebufferStatus(impl->output.fbo.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    return Error{ErrorKind::unsupported, "the G-buffer or output framebuffer is incomplete on this GL implementation"};
  return Compositor(std::move(impl));
}

Compositor::Compositor(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Compositor::Compositor(Compositor&&) noexcept = default;
Compositor& Compositor::operator=(Compositor&&) noexcept = default;
Compositor::~Compositor() = default;

Result<PassTimes> Compositor::render(const Scene& scene, const FrameParams& params) {
  Impl& m = *impl_;
  for (Eye e : kEyes) {
    const EyeFoveation& f = params.eyes[static_cast<std::size_t>(e)];
    if (!std::isfinite(f.sigma) || f.sigma < 1.0)
      return bad_input(std::string(eye_name(e)) + " eye: sigma must be a number >= 1");
    if (!std::isfinite(f.fx) || !std::isfinite(f.fy) || f.fx <= 0 || f.fy <= 0)
      return bad_input(std::string(eye_name(e)) + " eye: fx and fy must be numbers > 0");
  }
  const auto cpu_start = Clock::now();
  PassTimes times;
  m.timer.begin_frame();
  m.timer.mark(Pass::shadow);

  LightBlock lights = make_light_rig(scene.bounds, m.opt.point_lights);
  m.shadow_used = !scene.is_pattern();
  if (m.shadow_used) {
    m.shadow_pass(scene);
    m.timer.mark(Pass::shadow);
  } else {
    lights.counts.y = 0;
  }
  glNamedBufferSubData(m.lights_ubo.id(), 0, sizeof lights, &lights);
  glEnable(GL_FRAMEBUFFER_SRGB);

  for (Eye e : kEyes) {
    const std::size_t i = static_cast<std::size_t>(e);
    const EyeFoveation& f = params.eyes[i];
    const EyeView view = eye_view(scene, m.opt.model, e);
    const glm::ivec2 eye_origin(static_cast<int>(i) * m.eye_w, 0);
    // Fovea in GL's frame: origin bottom-left.
    const glm::vec2 fovea(static_cast<float>(image::sanitize_fovea(f.fovea_x)),
                          static_cast<float>(1.0 - image::sanitize_fovea(f.fovea_y)));

    // G-buffer.
    glBindFramebuffer(GL_FRAMEBUFFER, m.gbuffer.fbo.id());
    glViewport(0, 0, m.eye_w, m.eye_h);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearColor(0, 0, 0, 0);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (scene.is_pattern()) m.draw_pattern(scene);
    else m.draw_geometry(scene, view);
    glDisable(GL_DEPTH_TEST);
    m.timer.mark(Pass::gbuffer);

    if (params.method == Method::full) {
      glBindFramebuffer(GL_FRAMEBUFFER, m.output.fbo.id());
      glViewport(eye_origin.x, eye_origin.y, m.eye_w, m.eye_h);
      const float identity = static_cast<float>(image::kRmfrIdentityF);
      m.lighting_pass(m.gbuffer, eye_origin, fovea, glm::vec2(identity), view);
      m.timer.mark(Pass::lighting);
      m.last_size[i] = {m.eye_w, m.eye_h};
      continue;
    }

    const int w = image::rmfr_buffer_size(m.eye_w, f.sigma), h = image::rmfr_buffer_size(m.eye_h, f.sigma);
    const glm::vec2 fxy(static_cast<float>(image::rmfr_effective_f(f.fx, f.sigma)),
                        static_cast<float>(image::rmfr_effective_f(f.fy, f.sigma)));
    if (Status s = m.ensure_eye_buffers(i, w, h); !s) return s.error();
    m.last_size[i] = {w, h};
    const detail::SurfaceTargets& tg = *m.transformed[i];
    const detail::ColorTarget& rs = *m.reduced[i];

    // Mapping: G-buffer -> transformed G-buffer.
    glBindFramebuffer(GL_FRAMEBUFFER, tg.fbo.id());
    glViewport(0, 0, w, h);
    const GLuint mp = m.map_prog.id();
    glUseProgram(mp);
    set(mp, "u_buffer_size", glm::vec2(w, h));
    set(mp, "u_screen_size", glm::vec2(m.eye_w, m.eye_h));
    set(mp, "u_fovea", fovea);
    set(mp, "u_f", fxy);
    m.gbuffer.bind_textures();
    glBindVertexArray(m.empty_vao.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    m.timer.mark(Pass::mapping);

    // Lighting at w×h.
    glBindFramebuffer(GL_FRAMEBUFFER, rs.fbo.id());
    glViewport(0, 0, w, h);
    m.lighting_pass(tg, glm::ivec2(0), fovea, fxy, view);
    m.timer.mark(Pass::lighting);

    // Inverse mapping into this eye's half of the output.
    glBindFramebuffer(GL_FRAMEBUFFER, m.output.fbo.id());
    glViewport(eye_origin.x, eye_origin.y, m.eye_w, m.eye_h);
    const GLuint ip = m.inverse_prog.id();
    glUseProgram(ip);
    set(ip, "u_origin", eye_origin);
    set(ip, "u_screen_size", glm::vec2(m.eye_w, m.eye_h));
    set(ip, "u_fovea", fovea);
    set(ip, "u_f", fxy);
    glBindTextureUnit(0, rs.texture.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    m.timer.mark(Pass::inverse);
  }
  glFinish();
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
std::array<int, 2> Compositor::buffer_size(Eye e) const { return impl_->last_size[static_cast<std::size_t>(e)]; }

TargetMemory Compositor::memory() const {
  const Impl& m = *impl_;
  TargetMemory t;
  t.gbuffer = m.gbuffer.bytes();
  for (std::size_t i = 0; i < 2; ++i) {
    if (m.transformed[i]) t.transformed += m.transformed[i]->bytes();
    if (m.reduced[i]) t.reduced += m.reduced[i]->bytes();
  }
  t.output = m.output.bytes();
  t.shadow = m.shadow.bytes();
  return t;
}

std::string Compositor::renderer() const {
  auto str = [](GLenum e) {
    const auto* s = reinterpret_cast<const char*>(glGetString(e));
    return std::string(s ? s : "?");
  };
  return str(GL_VENDOR) + " / " + str(GL_RENDERER) + " / " + str(GL_VERSION);
}

}  // namespace foveal::render

// GL side of foveal-rmfr: the mapping pass (any G-buffer layout) and the resolve pass.
#include <map>
#include <string>
#include <vector>

#include "foveal/render/gl_objects.hpp"
#include "foveal/rmfr.hpp"
#include "gl_queries.hpp"
#include "glsl_files.hpp"

namespace foveal::rmfr {

namespace {

using detail::Kind;

constexpr const char* kFullscreenVert = R"(
void main() {  // one triangle covering the viewport, no vertex buffer
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

constexpr const char* kResolveFrag = R"(
layout(binding = 0) uniform sampler2D u_lit;
uniform ivec2 u_origin;      // the eye's viewport origin in the target
uniform vec2 u_screen_size;
uniform vec2 u_fovea;
uniform vec2 u_f;
uniform vec2 u_uv_scale;     // buffer size / texture size
uniform vec4 u_uv_clamp;     // texel centres at the buffer's edges (lo.xy, hi.xy)
uniform vec2 u_lens_center;  // GL frame, normalised
uniform vec3 u_lens_k;
uniform vec3 u_lens_scale;
uniform vec4 u_tan;
layout(location = 0) out vec4 o_color;

vec4 lit_at(vec2 p) {
  vec2 uv = foveal_rmfr_forward(p / u_screen_size, u_fovea, u_f) * u_uv_scale;
  return texture(u_lit, clamp(uv, u_uv_clamp.xy, u_uv_clamp.zw));
}

void main() {
  vec2 p = gl_FragCoord.xy - vec2(u_origin);
#ifndef LENS
  o_color = lit_at(p);
#else
  vec3 rgb;
  for (int c = 0; c < 3; ++c) {
    vec2 src = foveal_lens_source(p / u_screen_size, u_lens_center, u_lens_k, u_lens_scale[c], u_tan);
    bool inside = all(greaterThanEqual(src, vec2(0.0))) && all(lessThanEqual(src, vec2(1.0)));
    rgb[c] = inside ? lit_at(src * u_screen_size)[c] : 0.0;
  }
  o_color = vec4(rgb, 1.0);
#endif
}
)";

std::string info_log(GLuint object, bool program) {
  GLint len = 0;
  program ? glGetProgramiv(object, GL_INFO_LOG_LENGTH, &len) : glGetShaderiv(object, GL_INFO_LOG_LENGTH, &len);
  std::string log(static_cast<std::size_t>(len > 0 ? len : 1), '\0');
  program ? glGetProgramInfoLog(object, len, nullptr, log.data()) : glGetShaderInfoLog(object, len, nullptr, log.data());
  return log.c_str();
}

// "#version 450 core", `defines`, the mapping functions, then `body`, for both stages.
Result<gl::Program> build(const std::string& defines, const std::string& body, const char* name) {
  gl::Program program = gl::Program::create();
  const std::string head = "#version 450 core\n" + defines;
  const std::string vert = head + kFullscreenVert;
  const std::string frag = head + std::string(detail::kMappingGlsl) + body;
  std::vector<gl::Shader> shaders;
  for (const auto& [type, text] : {std::pair{GL_VERTEX_SHADER, &vert}, std::pair{GL_FRAGMENT_SHADER, &frag}}) {
    gl::Shader s(glCreateShader(type));
    const char* src = text->c_str();
    glShaderSource(s.id(), 1, &src, nullptr);
    glCompileShader(s.id());
    GLint ok = 0;
    glGetShaderiv(s.id(), GL_COMPILE_STATUS, &ok);
    if (!ok) return Error{ErrorKind::internal, std::string("rmfr: the ") + name + " shader does not compile:\n" + info_log(s.id(), false)};
    glAttachShader(program.id(), s.id());
    shaders.push_back(std::move(s));
  }
  glLinkProgram(program.id());
  GLint ok = 0;
  glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  if (!ok) return Error{ErrorKind::internal, std::string("rmfr: the ") + name + " program does not link:\n" + info_log(program.id(), true)};
  for (const gl::Shader& s : shaders) glDetachShader(program.id(), s.id());
  return program;
}

const char* prefix(Kind k) { return k == Kind::signed_int ? "i" : k == Kind::unsigned_int ? "u" : ""; }
char letter(Kind k) { return k == Kind::signed_int ? 'i' : k == Kind::unsigned_int ? 'u' : 'f'; }

// The mapping pass for one list of attachment kinds: texel k of output k is source k's
// texel at the screen pixel the reduced texel stands for.
std::string map_source(const std::vector<Kind>& kinds) {
  std::string decl, copy;
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    const std::string n = std::to_string(k);
    decl += "layout(binding = " + n + ") uniform " + prefix(kinds[k]) + "sampler2D u_src" + n + ";\n";
    decl += "layout(location = " + n + ") out " + prefix(kinds[k]) + "vec4 o_dst" + n + ";\n";
    copy += "  o_dst" + n + " = texelFetch(u_src" + n + ", src, 0);\n";
  }
  return "uniform vec2 u_buffer_size;\nuniform vec2 u_screen_size;\nuniform vec2 u_fovea;\nuniform vec2 u_f;\n" + decl +
         "void main() {\n  ivec2 src = foveal_rmfr_source_pixel(ivec2(gl_FragCoord.xy), u_buffer_size, u_screen_size, u_fovea, u_f);\n" +
         copy + "}\n";
}

GLint loc(GLuint p, const char* n) { return glGetUniformLocation(p, n); }
void set2(GLuint p, const char* n, double x, double y) { glProgramUniform2f(p, loc(p, n), static_cast<float>(x), static_cast<float>(y)); }
void set_mapping(GLuint p, const Plan& plan) {
  set2(p, "u_screen_size", plan.screen_w, plan.screen_h);
  set2(p, "u_fovea", plan.fovea_x, plan.fovea_y);
  set2(p, "u_f", plan.fx, plan.fy);
}

Status check_plan(const Plan& p) {
  if (p.screen_w < 1 || p.screen_h < 1 || p.buffer_w < 1 || p.buffer_h < 1 || p.buffer_w > p.screen_w || p.buffer_h > p.screen_h)
    return bad_input("rmfr: the plan's sizes are not those of plan_eye (screen " + std::to_string(p.screen_w) + "x" +
                     std::to_string(p.screen_h) + ", buffer " + std::to_string(p.buffer_w) + "x" + std::to_string(p.buffer_h) + ")");
  return {};
}

}  // namespace

struct Foveator::Impl {
  gl::VertexArray vao;
  gl::Sampler nearest, linear;
  std::array<gl::Program, 2> resolve;           // without, with the lens
  std::map<std::string, gl::Program> map_programs;  // by attachment kinds, e.g. "ffuf"
};

Result<Foveator> Foveator::create() {
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (!version || major * 10 + minor < 45)
    return Error{ErrorKind::unsupported, std::string("rmfr: needs a current OpenGL 4.5 context (found ") +
                                             (version ? version : "none") + ")"};
  auto impl = std::make_unique<Impl>();
  impl->vao = gl::VertexArray::create();
  impl->nearest = gl::make_clamped_sampler(GL_NEAREST);
  impl->linear = gl::make_clamped_sampler(GL_LINEAR);
  for (std::size_t lens = 0; lens < 2; ++lens) {
    auto p = build(lens ? "#define LENS 1\n" : "", kResolveFrag, "resolve");
    if (!p) return p.error();
    impl->resolve[lens] = std::move(*p);
  }
  return Foveator(std::move(impl));
}

Foveator::Foveator(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Foveator::Foveator(Foveator&&) noexcept = default;
Foveator& Foveator::operator=(Foveator&&) noexcept = default;
Foveator::~Foveator() = default;

Status Foveator::map(const Plan& plan, std::span<const unsigned> textures, unsigned dst) {
  if (Status s = check_plan(plan); !s) return s;
  const int max = detail::max_draw_buffers();
  if (textures.empty() || static_cast<int>(textures.size()) > max)
    return bad_input("rmfr: map: " + std::to_string(textures.size()) + " G-buffer textures (expected 1 to " + std::to_string(max) + ")");
  if (dst == 0) return bad_input("rmfr: map: the destination is the default framebuffer (expected the reduced G-buffer's)");
  std::vector<Kind> kinds;
  std::string key;
  std::vector<GLenum> draw;
  for (std::size_t k = 0; k < textures.size(); ++k) {
    const std::string what = "map: G-buffer texture " + std::to_string(k);
    auto t = detail::texture_info(textures[k], what);
    if (!t) return t.error();
    if (t->width < plan.screen_w || t->height < plan.screen_h)
      return bad_input("rmfr: " + what + " is " + std::to_string(t->width) + "x" + std::to_string(t->height) +
                       ", smaller than the eye's " + std::to_string(plan.screen_w) + "x" + std::to_string(plan.screen_h));
    const GLenum attachment = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(k);
    GLint type = GL_NONE, name = 0;
    glGetNamedFramebufferAttachmentParameteriv(dst, attachment, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    if (type != GL_TEXTURE) return bad_input("rmfr: map: the destination has no texture at colour attachment " + std::to_string(k));
    glGetNamedFramebufferAttachmentParameteriv(dst, attachment, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &name);
    auto d = detail::texture_info(static_cast<GLuint>(name), "map: destination attachment " + std::to_string(k));
    if (!d) return d.error();
    if (d->width < plan.buffer_w || d->height < plan.buffer_h)
      return bad_input("rmfr: map: destination attachment " + std::to_string(k) + " is " + std::to_string(d->width) + "x" +
                       std::to_string(d->height) + ", smaller than the buffer's " + std::to_string(plan.buffer_w) + "x" +
                       std::to_string(plan.buffer_h));
    if (d->kind != t->kind || d->depth)
      return bad_input("rmfr: map: destination attachment " + std::to_string(k) +
                       " does not match its source (integer sources need integer targets, depth a float colour target)");
    kinds.push_back(t->kind);
    key += letter(t->kind);
    draw.push_back(attachment);
  }
  glNamedFramebufferDrawBuffers(dst, static_cast<GLsizei>(draw.size()), draw.data());
  if (glCheckNamedFramebufferStatus(dst, GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    return bad_input("rmfr: map: the destination framebuffer is incomplete");

  auto found = impl_->map_programs.find(key);
  if (found == impl_->map_programs.end()) {
    auto p = build("", map_source(kinds), "mapping");
    if (!p) return p.error();
    found = impl_->map_programs.emplace(key, std::move(*p)).first;
  }
  const GLuint p = found->second.id();
  set2(p, "u_buffer_size", plan.buffer_w, plan.buffer_h);
  set_mapping(p, plan);

  detail::set_pass_state();
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, dst);
  glViewport(0, 0, plan.buffer_w, plan.buffer_h);
  glUseProgram(p);
  const auto n = static_cast<GLsizei>(textures.size());
  glBindTextures(0, n, textures.data());
  for (GLuint unit = 0; unit < static_cast<GLuint>(n); ++unit) glBindSampler(unit, impl_->nearest.id());
  glBindVertexArray(impl_->vao.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindSamplers(0, n, nullptr);
  return {};
}

Status Foveator::resolve(const Plan& plan, unsigned lit, unsigned dst, int x, int y, const Lens* lens) {
  if (Status s = check_plan(plan); !s) return s;
  auto t = detail::texture_info(lit, "resolve: the lit texture");
  if (!t) return t.error();
  if (t->width < plan.buffer_w || t->height < plan.buffer_h || t->kind != Kind::floating)
    return bad_input("rmfr: resolve: the lit texture (" + std::to_string(t->width) + "x" + std::to_string(t->height) +
                     ") is smaller than the buffer (" + std::to_string(plan.buffer_w) + "x" + std::to_string(plan.buffer_h) +
                     ") or not a colour texture");
  const GLuint p = impl_->resolve[lens ? 1 : 0].id();
  set_mapping(p, plan);
  glProgramUniform2i(p, loc(p, "u_origin"), x, y);
  const double tw = t->width, th = t->height;
  set2(p, "u_uv_scale", plan.buffer_w / tw, plan.buffer_h / th);
  glProgramUniform4f(p, loc(p, "u_uv_clamp"), static_cast<float>(0.5 / tw), static_cast<float>(0.5 / th),
                     static_cast<float>((plan.buffer_w - 0.5) / tw), static_cast<float>((plan.buffer_h - 0.5) / th));
  if (lens) {
    set2(p, "u_lens_center", lens->center_x, 1.0 - lens->center_y);
    glProgramUniform3f(p, loc(p, "u_lens_k"), static_cast<float>(lens->k1), static_cast<float>(lens->k2), static_cast<float>(lens->k3));
    glProgramUniform3f(p, loc(p, "u_lens_scale"), static_cast<float>(lens->channel_scale[0]),
                       static_cast<float>(lens->channel_scale[1]), static_cast<float>(lens->channel_scale[2]));
    const Frustum& f = plan.frustum;
    glProgramUniform4f(p, loc(p, "u_tan"), static_cast<float>(f.tan_left), static_cast<float>(f.tan_right),
                       static_cast<float>(f.tan_bottom), static_cast<float>(f.tan_top));
  }
  detail::set_pass_state();
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, dst);
  glViewport(x, y, plan.screen_w, plan.screen_h);
  glUseProgram(p);
  glBindTextureUnit(0, lit);
  glBindSampler(0, impl_->linear.id());
  glBindVertexArray(impl_->vao.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindSampler(0, 0);
  return {};
}

void set_uniforms(unsigned program, const Plan& plan) {
  const GLuint p = program;
  set2(p, "foveal_rmfr_buffer_size", plan.buffer_w, plan.buffer_h);
  set2(p, "foveal_rmfr_screen_size", plan.screen_w, plan.screen_h);
  set2(p, "foveal_rmfr_fovea", plan.fovea_x, plan.fovea_y);
  set2(p, "foveal_rmfr_f", plan.fx, plan.fy);
  const Frustum& f = plan.frustum;
  glProgramUniform4f(p, loc(p, "foveal_rmfr_tan"), static_cast<float>(f.tan_left), static_cast<float>(f.tan_right),
                     static_cast<float>(f.tan_bottom), static_cast<float>(f.tan_top));
}

}  // namespace foveal::rmfr

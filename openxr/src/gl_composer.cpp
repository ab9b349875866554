#include "gl_composer.hpp"

#include <GL/glcorearb.h>

#include <cmath>
#include <cstring>

namespace foveal::openxr {

// Every GL function the composer calls, loaded from the app's context.
#define FOVEAL_GL_FUNCTIONS(X)                                                                              \
  X(PFNGLGETINTEGERVPROC, GetIntegerv) X(PFNGLGETINTEGERI_VPROC, GetIntegeri_v) X(PFNGLISENABLEDPROC, IsEnabled) \
  X(PFNGLENABLEPROC, Enable) X(PFNGLDISABLEPROC, Disable) X(PFNGLVIEWPORTPROC, Viewport)                   \
  X(PFNGLUSEPROGRAMPROC, UseProgram) X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                          \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray) X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                    \
  X(PFNGLBINDTEXTUREPROC, BindTexture) X(PFNGLBINDSAMPLERPROC, BindSampler)                                \
  X(PFNGLGETBOOLEANVPROC, GetBooleanv) X(PFNGLCOLORMASKPROC, ColorMask) X(PFNGLDRAWARRAYSPROC, DrawArrays) \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)                                                  \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus) X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers) \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers) X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)         \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays) X(PFNGLGENSAMPLERSPROC, GenSamplers)                 \
  X(PFNGLDELETESAMPLERSPROC, DeleteSamplers) X(PFNGLSAMPLERPARAMETERIPROC, SamplerParameteri)             \
  X(PFNGLCREATESHADERPROC, CreateShader) X(PFNGLSHADERSOURCEPROC, ShaderSource)                           \
  X(PFNGLCOMPILESHADERPROC, CompileShader) X(PFNGLGETSHADERIVPROC, GetShaderiv)                           \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog) X(PFNGLCREATEPROGRAMPROC, CreateProgram)                 \
  X(PFNGLATTACHSHADERPROC, AttachShader) X(PFNGLLINKPROGRAMPROC, LinkProgram)                             \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv) X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                 \
  X(PFNGLDELETESHADERPROC, DeleteShader) X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                         \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation) X(PFNGLUNIFORM1IPROC, Uniform1i)                     \
  X(PFNGLUNIFORM1FPROC, Uniform1f) X(PFNGLUNIFORM2FPROC, Uniform2f) X(PFNGLUNIFORM4FPROC, Uniform4f)      \
  X(PFNGLREADPIXELSPROC, ReadPixels) X(PFNGLPIXELSTOREIPROC, PixelStorei) X(PFNGLGETSTRINGPROC, GetString) \
  X(PFNGLGETERRORPROC, GetError) X(PFNGLPOLYGONMODEPROC, PolygonMode) X(PFNGLBINDBUFFERPROC, BindBuffer)

struct GlComposer::Gl {
#define FOVEAL_GL_MEMBER(type, name) type name = nullptr;
  FOVEAL_GL_FUNCTIONS(FOVEAL_GL_MEMBER)
#undef FOVEAL_GL_MEMBER
};

namespace {

const char* const kVertex = R"(#version 330 core
void main() {
  // One triangle over the whole target.
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

// Tangent space: the output pixel's direction (x/-z, y/-z) in the eye's view, where the
// outer and inner views are both rectangles (their poses are identical).
const char* const kFragment = R"(#version 330 core
uniform sampler2D outer_tex, inner_tex;
uniform vec4 out_tan, outer_tan, inner_tan;  // left, right, down, up
uniform vec4 outer_uv, inner_uv;             // the sub-image: offset.xy, size.zw in texture units
uniform vec2 out_size;
uniform float band;                          // radians
out vec4 color;
void main() {
  vec2 p = gl_FragCoord.xy / out_size;
  vec2 t = vec2(mix(out_tan.x, out_tan.y, p.x), mix(out_tan.z, out_tan.w, p.y));
  vec2 ou = (t - outer_tan.xz) / (outer_tan.yw - outer_tan.xz);
  vec4 c = texture(outer_tex, outer_uv.xy + ou * outer_uv.zw);
  // The angle inside the inner view's nearest edge, per axis as the field of view states it.
  vec2 a = atan(t);
  vec4 e = atan(inner_tan);
  float d = min(min(a.x - e.x, e.y - a.x), min(a.y - e.z, e.w - a.y));
  if (d > 0.0) {
    vec2 iu = (t - inner_tan.xz) / (inner_tan.yw - inner_tan.xz);
    vec4 ci = texture(inner_tex, inner_uv.xy + iu * inner_uv.zw);
    c = mix(c, ci, band > 0.0 ? smoothstep(0.0, band, d) : 1.0);
  }
  color = c;
}
)";

/// The state the composer changes, as the app had it.
struct SavedState {
  GLint program, draw_fbo, read_fbo, vao, active_texture, textures[2], samplers[2], viewport[4], polygon_mode[2];
  GLboolean color_mask[4];
  GLboolean enabled[7];
};
constexpr GLenum kCaps[7] = {GL_BLEND, GL_DEPTH_TEST, GL_SCISSOR_TEST, GL_CULL_FACE, GL_STENCIL_TEST,
                             GL_FRAMEBUFFER_SRGB, GL_RASTERIZER_DISCARD};

}  // namespace

std::unique_ptr<GlComposer> GlComposer::create(GlGetProcAddress get_proc, std::string& error) {
  if (!get_proc) {
    error = "no way to load OpenGL functions from the app's graphics binding";
    return nullptr;
  }
  std::unique_ptr<GlComposer> c(new GlComposer);
  c->gl_ = std::make_unique<Gl>();
  Gl& gl = *c->gl_;
#define FOVEAL_GL_LOAD(type, name)                                             \
  gl.name = reinterpret_cast<type>(get_proc("gl" #name));                     \
  if (!gl.name) {                                                              \
    error = "the app's OpenGL context lacks gl" #name;                         \
    return nullptr;                                                            \
  }
  FOVEAL_GL_FUNCTIONS(FOVEAL_GL_LOAD)
#undef FOVEAL_GL_LOAD
  auto compile = [&](GLenum type, const char* src) -> GLuint {
    const GLuint s = gl.CreateShader(type);
    gl.ShaderSource(s, 1, &src, nullptr);
    gl.CompileShader(s);
    GLint ok = 0;
    gl.GetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char log[512] = {};
      gl.GetShaderInfoLog(s, sizeof log, nullptr, log);
      error = std::string("the composition shader does not compile on the app's context: ") + log;
      gl.DeleteShader(s);
      return 0;
    }
    return s;
  };
  const GLuint vs = compile(GL_VERTEX_SHADER, kVertex);
  const GLuint fs = vs ? compile(GL_FRAGMENT_SHADER, kFragment) : 0;
  if (!fs) {
    if (vs) gl.DeleteShader(vs);
    return nullptr;
  }
  GLint saved_program = 0;
  gl.GetIntegerv(GL_CURRENT_PROGRAM, &saved_program);
  c->program_ = gl.CreateProgram();
  gl.AttachShader(c->program_, vs);
  gl.AttachShader(c->program_, fs);
  gl.LinkProgram(c->program_);
  gl.DeleteShader(vs);
  gl.DeleteShader(fs);
  GLint linked = 0;
  gl.GetProgramiv(c->program_, GL_LINK_STATUS, &linked);
  if (!linked) {
    error = "the composition program does not link on the app's context";
    return nullptr;  // the destructor deletes it
  }
  c->u_outer_tan_ = gl.GetUniformLocation(c->program_, "outer_tan");
  c->u_outer_uv_ = gl.GetUniformLocation(c->program_, "outer_uv");
  c->u_inner_tan_ = gl.GetUniformLocation(c->program_, "inner_tan");
  c->u_inner_uv_ = gl.GetUniformLocation(c->program_, "inner_uv");
  c->u_out_tan_ = gl.GetUniformLocation(c->program_, "out_tan");
  c->u_out_size_ = gl.GetUniformLocation(c->program_, "out_size");
  c->u_band_ = gl.GetUniformLocation(c->program_, "band");
  c->u_outer_tex_ = gl.GetUniformLocation(c->program_, "outer_tex");
  c->u_inner_tex_ = gl.GetUniformLocation(c->program_, "inner_tex");
  gl.UseProgram(c->program_);
  gl.Uniform1i(c->u_outer_tex_, 0);
  gl.Uniform1i(c->u_inner_tex_, 1);
  gl.UseProgram(static_cast<GLuint>(saved_program));
  gl.GenVertexArrays(1, &c->vao_);
  gl.GenFramebuffers(1, &c->fbo_);
  gl.GenSamplers(1, &c->sampler_);
  gl.SamplerParameteri(c->sampler_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl.SamplerParameteri(c->sampler_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl.SamplerParameteri(c->sampler_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl.SamplerParameteri(c->sampler_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return c;
}

GlComposer::~GlComposer() {
  if (!gl_ || !gl_->DeleteProgram) return;
  if (program_) gl_->DeleteProgram(program_);
  if (vao_) gl_->DeleteVertexArrays(1, &vao_);
  if (fbo_) gl_->DeleteFramebuffers(1, &fbo_);
  if (sampler_) gl_->DeleteSamplers(1, &sampler_);
}

namespace {

void save(const auto& gl, SavedState& s) {
  gl.GetIntegerv(GL_CURRENT_PROGRAM, &s.program);
  gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s.draw_fbo);
  gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s.read_fbo);
  gl.GetIntegerv(GL_VERTEX_ARRAY_BINDING, &s.vao);
  gl.GetIntegerv(GL_ACTIVE_TEXTURE, &s.active_texture);
  for (int u = 0; u < 2; ++u) {
    gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + u));
    gl.GetIntegerv(GL_TEXTURE_BINDING_2D, &s.textures[u]);
    gl.GetIntegerv(GL_SAMPLER_BINDING, &s.samplers[u]);
  }
  gl.GetIntegerv(GL_VIEWPORT, s.viewport);
  gl.GetIntegerv(GL_POLYGON_MODE, s.polygon_mode);
  gl.GetBooleanv(GL_COLOR_WRITEMASK, s.color_mask);
  for (int i = 0; i < 7; ++i) s.enabled[i] = gl.IsEnabled(kCaps[i]);
}

void restore(const auto& gl, const SavedState& s) {
  for (int i = 0; i < 7; ++i) (s.enabled[i] ? gl.Enable : gl.Disable)(kCaps[i]);
  gl.ColorMask(s.color_mask[0], s.color_mask[1], s.color_mask[2], s.color_mask[3]);
  gl.PolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(s.polygon_mode[0]));
  gl.Viewport(s.viewport[0], s.viewport[1], s.viewport[2], s.viewport[3]);
  for (int u = 0; u < 2; ++u) {
    gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + u));
    gl.BindTexture(GL_TEXTURE_2D, static_cast<GLuint>(s.textures[u]));
    gl.BindSampler(static_cast<GLuint>(u), static_cast<GLuint>(s.samplers[u]));
  }
  gl.ActiveTexture(static_cast<GLenum>(s.active_texture));
  gl.BindVertexArray(static_cast<GLuint>(s.vao));
  gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(s.draw_fbo));
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(s.read_fbo));
  gl.UseProgram(static_cast<GLuint>(s.program));
}

void set_rect(const auto& gl, GLint loc, const TanRect& t) { gl.Uniform4f(loc, t.left, t.right, t.down, t.up); }

void set_uv(const auto& gl, GLint loc, const ComposeSource& s) {
  const float iw = 1.0f / static_cast<float>(s.image_w), ih = 1.0f / static_cast<float>(s.image_h);
  gl.Uniform4f(loc, static_cast<float>(s.x) * iw, static_cast<float>(s.y) * ih, static_cast<float>(s.w) * iw,
               static_cast<float>(s.h) * ih);
}

}  // namespace

bool GlComposer::compose(const ComposeSource& outer, const ComposeSource& inner, std::uint32_t target, int w, int h,
                         const TanRect& out, float blend_deg, bool srgb) {
  const Gl& gl = *gl_;
  SavedState saved{};
  save(gl, saved);
  gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo_);
  gl.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target, 0);
  const bool complete = gl.CheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  if (complete) {
    for (GLenum cap : kCaps) gl.Disable(cap);
    if (srgb) gl.Enable(GL_FRAMEBUFFER_SRGB);
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.PolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    gl.Viewport(0, 0, w, h);
    gl.UseProgram(program_);
    gl.BindVertexArray(vao_);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, outer.texture);
    gl.BindSampler(0, sampler_);
    gl.ActiveTexture(GL_TEXTURE1);
    gl.BindTexture(GL_TEXTURE_2D, inner.texture);
    gl.BindSampler(1, sampler_);
    set_rect(gl, u_outer_tan_, outer.fov);
    set_rect(gl, u_inner_tan_, inner.fov);
    set_rect(gl, u_out_tan_, out);
    set_uv(gl, u_outer_uv_, outer);
    set_uv(gl, u_inner_uv_, inner);
    gl.Uniform2f(u_out_size_, static_cast<float>(w), static_cast<float>(h));
    gl.Uniform1f(u_band_, blend_deg * 3.14159265f / 180.0f);
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
  }
  gl.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
  restore(gl, saved);
  return complete;
}

bool GlComposer::read(std::uint32_t target, int w, int h, std::vector<std::uint8_t>& rgba) {
  const Gl& gl = *gl_;
  SavedState saved{};
  save(gl, saved);
  GLint pack_alignment = 4, pack_buffer = 0;
  gl.GetIntegerv(GL_PACK_ALIGNMENT, &pack_alignment);
  gl.GetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pack_buffer);
  gl.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);  // into client memory, whatever the app had bound
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
  gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target, 0);
  const bool ok = gl.CheckFramebufferStatus(GL_READ_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  std::vector<std::uint8_t> bottom_up;
  if (ok) {
    bottom_up.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
    gl.PixelStorei(GL_PACK_ALIGNMENT, pack_alignment);
  }
  gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
  gl.BindBuffer(GL_PIXEL_PACK_BUFFER, static_cast<GLuint>(pack_buffer));
  restore(gl, saved);
  if (!ok) return false;
  const std::size_t row = static_cast<std::size_t>(w) * 4;
  rgba.resize(bottom_up.size());
  for (int y = 0; y < h; ++y)
    std::memcpy(rgba.data() + static_cast<std::size_t>(y) * row,
                bottom_up.data() + static_cast<std::size_t>(h - 1 - y) * row, row);
  return true;
}

}  // namespace foveal::openxr

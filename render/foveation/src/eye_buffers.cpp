// One eye's reduced G-buffer and lit buffer, for applications that want the library to
// own them.
#include <cstdio>
#include <vector>

#include "foveal/render/gl_objects.hpp"
#include "foveal/rmfr.hpp"
#include "gl_queries.hpp"

namespace foveal::rmfr {

namespace {

constexpr int kMaxSize = 16384;

void set_filter(GLuint t, GLint filter) {
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, filter);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, filter);
  glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

// A w×h texture of `format` (a depth format becomes R32F: the mapping pass writes depth
// as a colour). Errors: GL refusing the format, a stencil-only format.
Result<gl::Texture> make_target(GLenum format, int w, int h, GLint filter, const std::string& what) {
  gl::Texture t = gl::make_texture_2d(format, w, h);
  GLint allocated = 0;
  glGetTextureLevelParameteriv(t.id(), 0, GL_TEXTURE_WIDTH, &allocated);
  if (allocated != w) {  // GL refused the format (GL_INVALID_ENUM): no storage
    char hex[16];
    std::snprintf(hex, sizeof hex, "0x%04x", format);
    return Error{ErrorKind::unsupported, "rmfr: " + what + ": GL has no texture format " + hex};
  }
  auto info = detail::texture_info(t.id(), what);
  if (!info) return info.error();
  if (info->depth) t = gl::make_texture_2d(GL_R32F, w, h);
  set_filter(t.id(), filter);
  return t;
}

}  // namespace

struct EyeBuffers::Impl {
  std::vector<GLenum> formats;
  GLenum lit_format = 0;
  int width = 0, height = 0;
  std::vector<gl::Texture> gbuffer;
  gl::Texture lit;
  gl::Framebuffer gbuffer_fbo, lit_fbo;

  Status allocate(int w, int h) {
    if (w < 1 || h < 1 || w > kMaxSize || h > kMaxSize)
      return bad_input("rmfr: reduced buffers of " + std::to_string(w) + "x" + std::to_string(h) + " (expected [1, 16384])");
    std::vector<gl::Texture> g;
    for (std::size_t k = 0; k < formats.size(); ++k) {
      auto t = make_target(formats[k], w, h, GL_NEAREST, "reduced G-buffer attachment " + std::to_string(k));
      if (!t) return t.error();
      g.push_back(std::move(*t));
    }
    auto l = make_target(lit_format, w, h, GL_LINEAR, "lit buffer");
    if (!l) return l.error();
    gl::Framebuffer gf = gl::Framebuffer::create(), lf = gl::Framebuffer::create();
    std::vector<GLenum> draw;
    for (std::size_t k = 0; k < g.size(); ++k) {
      draw.push_back(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(k));
      glNamedFramebufferTexture(gf.id(), draw.back(), g[k].id(), 0);
    }
    glNamedFramebufferDrawBuffers(gf.id(), static_cast<GLsizei>(draw.size()), draw.data());
    glNamedFramebufferTexture(lf.id(), GL_COLOR_ATTACHMENT0, l->id(), 0);
    glNamedFramebufferDrawBuffer(lf.id(), GL_COLOR_ATTACHMENT0);
    for (GLuint f : {gf.id(), lf.id()})
      if (glCheckNamedFramebufferStatus(f, GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return Error{ErrorKind::unsupported, "rmfr: GL cannot render to these formats (incomplete framebuffer)"};
    gbuffer = std::move(g), lit = std::move(*l), gbuffer_fbo = std::move(gf), lit_fbo = std::move(lf);
    width = w, height = h;
    return {};
  }
};

Result<EyeBuffers> EyeBuffers::create(int w, int h, std::span<const unsigned> formats, unsigned lit_format) {
  const int max = detail::max_draw_buffers();
  if (formats.empty() || static_cast<int>(formats.size()) > max)
    return bad_input("rmfr: " + std::to_string(formats.size()) + " G-buffer formats (expected 1 to " + std::to_string(max) + ")");
  auto impl = std::make_unique<Impl>();
  impl->formats.assign(formats.begin(), formats.end());
  impl->lit_format = lit_format;
  if (Status s = impl->allocate(w, h); !s) return s.error();
  return EyeBuffers(std::move(impl));
}

EyeBuffers::EyeBuffers(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
EyeBuffers::EyeBuffers(EyeBuffers&&) noexcept = default;
EyeBuffers& EyeBuffers::operator=(EyeBuffers&&) noexcept = default;
EyeBuffers::~EyeBuffers() = default;

Status EyeBuffers::fit(const Plan& plan) {
  if (plan.buffer_w == impl_->width && plan.buffer_h == impl_->height) return {};
  return impl_->allocate(plan.buffer_w, plan.buffer_h);
}

int EyeBuffers::width() const { return impl_->width; }
int EyeBuffers::height() const { return impl_->height; }
std::size_t EyeBuffers::attachments() const { return impl_->gbuffer.size(); }
unsigned EyeBuffers::gbuffer_framebuffer() const { return impl_->gbuffer_fbo.id(); }
unsigned EyeBuffers::gbuffer_texture(std::size_t i) const { return i < impl_->gbuffer.size() ? impl_->gbuffer[i].id() : 0; }
unsigned EyeBuffers::lit_framebuffer() const { return impl_->lit_fbo.id(); }
unsigned EyeBuffers::lit_texture() const { return impl_->lit.id(); }

}  // namespace foveal::rmfr

#include "render_targets.hpp"

#include <vector>

namespace foveal::render::detail {

namespace {
void nearest_clamped(GLuint t) {
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}
}  // namespace

SurfaceTargets SurfaceTargets::create(int width, int height, bool depth_as_color) {
  SurfaceTargets s;
  s.width = width;
  s.height = height;
  s.albedo = gl::make_texture_2d(GL_SRGB8_ALPHA8, width, height);
  s.normal = gl::make_texture_2d(GL_RG16_SNORM, width, height);
  s.material = gl::make_texture_2d(GL_RGBA8, width, height);
  s.emissive = gl::make_texture_2d(GL_R11F_G11F_B10F, width, height);
  s.depth = gl::make_texture_2d(depth_as_color ? GL_R32F : GL_DEPTH_COMPONENT32F, width, height);
  s.fbo = gl::Framebuffer::create();
  const GLuint f = s.fbo.id();
  const GLuint color[] = {s.albedo.id(), s.normal.id(), s.material.id(), s.emissive.id(), s.depth.id()};
  for (GLuint t : color) nearest_clamped(t);
  for (int i = 0; i < 4; ++i) glNamedFramebufferTexture(f, GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i), color[i], 0);
  if (depth_as_color) {
    glNamedFramebufferTexture(f, GL_COLOR_ATTACHMENT4, s.depth.id(), 0);
    const GLenum bufs[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3, GL_COLOR_ATTACHMENT4};
    glNamedFramebufferDrawBuffers(f, 5, bufs);
  } else {
    glNamedFramebufferTexture(f, GL_DEPTH_ATTACHMENT, s.depth.id(), 0);
    const GLenum bufs[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
    glNamedFramebufferDrawBuffers(f, 4, bufs);
  }
  return s;
}

void SurfaceTargets::bind_textures() const {
  const std::array<GLuint, 5> t = textures();
  glBindTextures(0, static_cast<GLsizei>(t.size()), t.data());
}

ColorTarget ColorTarget::create(int width, int height, GLenum format, bool linear_filter) {
  ColorTarget c;
  c.width = width;
  c.height = height;
  c.bytes_per_pixel = format == GL_RGBA32F ? 16 : 4;
  c.texture = gl::make_texture_2d(format, width, height);
  nearest_clamped(c.texture.id());
  if (linear_filter) {
    glTextureParameteri(c.texture.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(c.texture.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  }
  c.fbo = gl::Framebuffer::create();
  glNamedFramebufferTexture(c.fbo.id(), GL_COLOR_ATTACHMENT0, c.texture.id(), 0);
  glNamedFramebufferDrawBuffer(c.fbo.id(), GL_COLOR_ATTACHMENT0);
  return c;
}

ColorTarget ColorTarget::create_shadow(int size) {
  ColorTarget c;
  c.width = c.height = size;
  c.texture = gl::make_texture_2d(GL_DEPTH_COMPONENT32F, size, size);
  const GLuint t = c.texture.id();
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTextureParameteri(t, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  c.fbo = gl::Framebuffer::create();
  glNamedFramebufferTexture(c.fbo.id(), GL_DEPTH_ATTACHMENT, t, 0);
  glNamedFramebufferDrawBuffer(c.fbo.id(), GL_NONE);
  return c;
}

VisibilityTarget VisibilityTarget::create(int width, int height) {
  VisibilityTarget v;
  v.width = width;
  v.height = height;
  v.ids = gl::make_texture_2d(GL_RG32UI, width, height);
  v.depth = gl::make_texture_2d(GL_DEPTH_COMPONENT32F, width, height);
  nearest_clamped(v.ids.id());
  nearest_clamped(v.depth.id());
  v.fbo = gl::Framebuffer::create();
  glNamedFramebufferTexture(v.fbo.id(), GL_COLOR_ATTACHMENT0, v.ids.id(), 0);
  glNamedFramebufferTexture(v.fbo.id(), GL_DEPTH_ATTACHMENT, v.depth.id(), 0);
  glNamedFramebufferDrawBuffer(v.fbo.id(), GL_COLOR_ATTACHMENT0);
  return v;
}

MaterialSurface MaterialSurface::create(int width, int height) {
  MaterialSurface m;
  m.surface = SurfaceTargets::create(width, height, true);
  m.material_depth = gl::make_texture_2d(GL_DEPTH_COMPONENT32F, width, height);
  nearest_clamped(m.material_depth.id());
  glNamedFramebufferTexture(m.surface.fbo.id(), GL_DEPTH_ATTACHMENT, m.material_depth.id(), 0);
  return m;
}

MaterialTiles MaterialTiles::create(int width, int height, int tile, std::size_t slots) {
  MaterialTiles t;
  t.across = (width + tile - 1) / tile;
  t.down = (height + tile - 1) / tile;
  t.slots = slots;
  std::vector<GLuint> empty(4 * slots, 0);
  for (std::size_t k = 0; k < slots; ++k) empty[4 * k] = 6;  // six vertices: one quad per instance
  t.empty = gl::Buffer::create();
  glNamedBufferStorage(t.empty.id(), static_cast<GLsizeiptr>(slots * 16), empty.data(), 0);
  t.commands = gl::Buffer::create();
  glNamedBufferStorage(t.commands.id(), static_cast<GLsizeiptr>(slots * 16), nullptr, 0);
  t.lists = gl::Buffer::create();
  glNamedBufferStorage(t.lists.id(), static_cast<GLsizeiptr>(slots * t.count() * 4), nullptr, 0);
  return t;
}

}  // namespace foveal::render::detail

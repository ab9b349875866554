#include "render_targets.hpp"

#include <vector>

#include "foveal/render/scene_types.hpp"

namespace foveal::render::detail {

namespace {
void nearest_clamped(GLuint t) {
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}
}  // namespace

SurfaceLayout SurfaceLayout::for_features(unsigned features) {
  // Coat: factor, roughness and its own normal (octahedral, signed); sheen: colour and
  // roughness; specular: √F0 (resolution where F0 is small) and F90 (docs/scenes.md).
  // Anisotropy: strength and the world-space direction of the stretched lobe (octahedral);
  // iridescence: factor, film thickness / 2000 nm, (film ior − 1) / 4 (16 bits: the film's
  // colour cycles every ~200 nm of thickness).
  static const Target kTargets[] = {
      {feature_clearcoat, "clearcoat", GL_RGBA16_SNORM, 8},
      {feature_specular, "specular", GL_RGBA8, 4},
      {feature_sheen, "sheen", GL_RGBA8, 4},
      {feature_anisotropy, "anisotropy", GL_RGBA16_SNORM, 8},
      {feature_iridescence, "iridescence", GL_RGBA16, 8},
  };
  SurfaceLayout l;
  for (const Target& t : kTargets)
    if ((features & t.feature) && l.targets.size() < kMaxTargets) {
      l.targets.push_back(t);
      l.features |= t.feature;
    }
  l.features |= features & feature_transmission;
  if (features & feature_transmission) l.forward.push_back("transmission");
  return l;
}

std::size_t SurfaceLayout::bytes_per_pixel() const {
  std::size_t b = kCoreBytesPerPixel;
  for (const Target& t : targets) b += t.bytes_per_pixel;
  return b;
}

namespace {
std::string upper(const char* name) {
  std::string u = name;
  for (char& c : u) c = static_cast<char>(c - 'a' + 'A');
  return u;
}
}  // namespace

std::string SurfaceLayout::defines() const {
  std::string d;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const std::string u = upper(targets[i].name);
    d += "#define FEATURE_" + u + " 1\n#define " + u + "_LOCATION " + std::to_string(kFirstLocation + i) + "\n#define " + u +
         "_UNIT " + std::to_string(kFirstUnit + i) + "\n";
  }
  for (const char* f : forward) d += "#define FEATURE_" + upper(f) + " 1\n";
  return d;
}

std::string SurfaceLayout::variant_name() const {
  std::string n = "metal-rough";
  for (const Target& t : targets) n += std::string("+") + t.name;
  for (const char* f : forward) n += std::string("+") + f;
  return n;
}

SurfaceTargets SurfaceTargets::create(int width, int height, bool depth_as_color, const SurfaceLayout& layout) {
  SurfaceTargets s;
  s.width = width;
  s.height = height;
  s.bytes_per_pixel = layout.bytes_per_pixel();
  s.albedo = gl::make_texture_2d(GL_SRGB8_ALPHA8, width, height);
  s.normal = gl::make_texture_2d(GL_RG16_SNORM, width, height);
  s.material = gl::make_texture_2d(GL_RGBA8, width, height);
  s.emissive = gl::make_texture_2d(GL_R11F_G11F_B10F, width, height);
  s.depth = gl::make_texture_2d(depth_as_color ? GL_R32F : GL_DEPTH_COMPONENT32F, width, height);
  for (const SurfaceLayout::Target& t : layout.targets) s.features.push_back(gl::make_texture_2d(t.format, width, height));
  s.fbo = gl::Framebuffer::create();
  const GLuint f = s.fbo.id();
  const std::vector<GLuint> all = s.textures();
  for (GLuint t : all) nearest_clamped(t);
  std::vector<GLenum> bufs;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const GLenum attachment = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
    if (i == 4 && !depth_as_color) {  // depth as the depth attachment; location 4 writes nothing
      glNamedFramebufferTexture(f, GL_DEPTH_ATTACHMENT, all[i], 0);
      bufs.push_back(GL_NONE);
      continue;
    }
    glNamedFramebufferTexture(f, attachment, all[i], 0);
    bufs.push_back(attachment);
  }
  if (!depth_as_color && bufs.size() == 5) bufs.pop_back();  // no trailing GL_NONE
  glNamedFramebufferDrawBuffers(f, static_cast<GLsizei>(bufs.size()), bufs.data());
  return s;
}

std::vector<GLuint> SurfaceTargets::textures() const {
  std::vector<GLuint> t = {albedo.id(), normal.id(), material.id(), emissive.id(), depth.id()};
  for (const gl::Texture& f : features) t.push_back(f.id());
  return t;
}

void SurfaceTargets::bind_textures() const {
  const std::vector<GLuint> t = textures();
  glBindTextures(0, 5, t.data());
  if (t.size() > 5) glBindTextures(SurfaceLayout::kFirstUnit, static_cast<GLsizei>(t.size() - 5), t.data() + 5);
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

MaterialSurface MaterialSurface::create(int width, int height, const SurfaceLayout& layout) {
  MaterialSurface m;
  m.surface = SurfaceTargets::create(width, height, true, layout);
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

#include "gl_queries.hpp"

namespace foveal::rmfr::detail {

namespace {
Kind kind_of(GLint component_type) {
  if (component_type == GL_INT) return Kind::signed_int;
  if (component_type == GL_UNSIGNED_INT) return Kind::unsigned_int;
  return Kind::floating;
}
}  // namespace

Result<TextureInfo> texture_info(GLuint texture, const std::string& what) {
  if (texture == 0 || !glIsTexture(texture)) return bad_input("rmfr: " + what + ": " + std::to_string(texture) + " is no texture");
  GLint target = 0;
  glGetTextureParameteriv(texture, GL_TEXTURE_TARGET, &target);
  if (target != GL_TEXTURE_2D) return bad_input("rmfr: " + what + ": texture " + std::to_string(texture) + " is not a 2D texture");
  TextureInfo t;
  GLint v = 0, red = 0, depth = 0;
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_WIDTH, &t.width);
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_HEIGHT, &t.height);
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_INTERNAL_FORMAT, &v);
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_RED_TYPE, &red);
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_DEPTH_TYPE, &depth);
  t.internal_format = static_cast<GLenum>(v);
  t.depth = depth != GL_NONE;
  if (!t.depth && red == GL_NONE)
    return bad_input("rmfr: " + what + ": texture " + std::to_string(texture) + " has neither colour nor depth (stencil only?)");
  t.kind = t.depth ? Kind::floating : kind_of(red);
  return t;
}

int max_draw_buffers() {
  GLint n = 0;
  glGetIntegerv(GL_MAX_DRAW_BUFFERS, &n);
  return n;
}

void set_pass_state() {
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_FRAMEBUFFER_SRGB);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

}  // namespace foveal::rmfr::detail

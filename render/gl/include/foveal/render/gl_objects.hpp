#pragma once
// Move-only owners of GL object names. Each deletes its object on destruction; they
// must be destroyed while the context that created them is current. Not thread-safe:
// use them on the thread that owns the context.
#include <utility>

#include "foveal/render/gl.hpp"

namespace foveal::gl {

template <class Traits>
class Handle {
 public:
  Handle() = default;
  explicit Handle(GLuint id) : id_(id) {}
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }

  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_) Traits::destroy(id_);
    id_ = 0;
  }
  /// Creates a new object (DSA glCreate*).
  static Handle create() { return Handle(Traits::create()); }

 private:
  GLuint id_ = 0;
};

namespace detail {
struct BufferTraits {
  static GLuint create() { GLuint id = 0; glCreateBuffers(1, &id); return id; }
  static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct VertexArrayTraits {
  static GLuint create() { GLuint id = 0; glCreateVertexArrays(1, &id); return id; }
  static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct FramebufferTraits {
  static GLuint create() { GLuint id = 0; glCreateFramebuffers(1, &id); return id; }
  static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct SamplerTraits {
  static GLuint create() { GLuint id = 0; glCreateSamplers(1, &id); return id; }
  static void destroy(GLuint id) { glDeleteSamplers(1, &id); }
};
struct ProgramTraits {
  static GLuint create() { return glCreateProgram(); }
  static void destroy(GLuint id) { glDeleteProgram(id); }
};
struct ShaderTraits {
  static void destroy(GLuint id) { glDeleteShader(id); }
};
struct TextureTraits {
  static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};
struct QueryTraits {
  static void destroy(GLuint id) { glDeleteQueries(1, &id); }
};
}  // namespace detail

using Buffer = Handle<detail::BufferTraits>;
using VertexArray = Handle<detail::VertexArrayTraits>;
using Framebuffer = Handle<detail::FramebufferTraits>;
using Sampler = Handle<detail::SamplerTraits>;
using Program = Handle<detail::ProgramTraits>;
using Shader = Handle<detail::ShaderTraits>;    ///< create with glCreateShader(type)
using Texture = Handle<detail::TextureTraits>;  ///< create with glCreateTextures(target)
using Query = Handle<detail::QueryTraits>;      ///< create with make_query(target)

/// A texture of `target` (DSA).
inline Texture make_texture(GLenum target) {
  GLuint id = 0;
  glCreateTextures(target, 1, &id);
  return Texture(id);
}

/// A query object of `target` (DSA: it has its type before its first glBeginQuery).
inline Query make_query(GLenum target) {
  GLuint id = 0;
  glCreateQueries(target, 1, &id);
  return Query(id);
}

/// A sampler that filters with `filter` both ways, clamps to the edge and compares
/// nothing (a depth texture read as values).
inline Sampler make_clamped_sampler(GLint filter) {
  Sampler s = Sampler::create();
  glSamplerParameteri(s.id(), GL_TEXTURE_MIN_FILTER, filter);
  glSamplerParameteri(s.id(), GL_TEXTURE_MAG_FILTER, filter);
  glSamplerParameteri(s.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glSamplerParameteri(s.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glSamplerParameteri(s.id(), GL_TEXTURE_COMPARE_MODE, GL_NONE);
  return s;
}

/// A 2D texture with storage for `levels` mip levels.
inline Texture make_texture_2d(GLenum internal_format, int width, int height, int levels = 1) {
  Texture t = make_texture(GL_TEXTURE_2D);
  glTextureStorage2D(t.id(), levels, internal_format, width, height);
  return t;
}

}  // namespace foveal::gl

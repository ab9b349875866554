#pragma once
// Quad views composed on the app's OpenGL context (composer.hpp). The app's context is
// current on the thread that calls xrEndFrame (the OpenGL bindings' rule); every piece of
// GL state the composer touches is put back. Objects are made once, at the first frame;
// a frame allocates nothing.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "composer.hpp"

namespace foveal::openxr {

using GlGetProcAddress = void* (*)(const char*);

class GlComposer final : public Composer {
 public:
  /// Loads the GL entry points through `get_proc` and builds the program; null with
  /// `error` set when the context cannot (no OpenGL 3.3 core, a missing function).
  static std::unique_ptr<GlComposer> create(GlGetProcAddress get_proc, std::string& error);
  ~GlComposer();
  GlComposer(const GlComposer&) = delete;
  GlComposer& operator=(const GlComposer&) = delete;

  /// target.image: a GL_TEXTURE_2D; an sRGB target format (GL_SRGB8_ALPHA8, GL_SRGB8) is
  /// encoded on write and blended linear. A source with `array` set is a GL_TEXTURE_2D_ARRAY
  /// sampled at its `layer` (the program for that pair of sampler types is built the first
  /// time it is needed). False when the framebuffer is incomplete or that program fails.
  bool compose(const ComposeSource& outer, const ComposeSource& inner, const ComposeTarget& target, const TanRect& out,
               float blend_deg) override;
  bool read(const ComposeTarget& target, std::vector<std::uint8_t>& rgba) override;

 private:
  GlComposer() = default;
  struct Gl;
  /// compose.glsl built for one pair of sampler types: bit 0, the outer view is a layer of
  /// a GL_TEXTURE_2D_ARRAY; bit 1, the inner view is.
  struct Program {
    std::uint32_t id = 0;
    int u_outer_tan = -1, u_outer_uv = -1, u_inner_tan = -1, u_inner_uv = -1, u_out_tan = -1, u_band = -1,
        u_out_size = -1, u_outer_layer = -1, u_inner_layer = -1;
  };
  /// Builds programs_[variant] (at the first frame that needs it); false with `error` set.
  bool build(int variant, std::string& error);

  std::unique_ptr<Gl> gl_;
  Program programs_[4];
  bool program_failed_[4] = {};
  std::uint32_t vao_ = 0, fbo_ = 0, sampler_ = 0;
};

}  // namespace foveal::openxr

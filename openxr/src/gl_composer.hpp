#pragma once
// Quad views composed on the app's OpenGL context: each eye's inner view blended over
// its upsampled outer view into a stereo image the layer submits (docs/openxr.md,
// "Composition"). The app's context is current on the thread that calls xrEndFrame (the
// OpenGL bindings' rule); every piece of GL state the composer touches is put back.
// Objects are made once, at the first frame; a frame allocates nothing.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "inset.hpp"

namespace foveal::openxr {

using GlGetProcAddress = void* (*)(const char*);

/// One source image: a GL texture, the rectangle the app drew into, and its view's field.
struct ComposeSource {
  std::uint32_t texture = 0;
  int image_w = 0, image_h = 0;       ///< the texture's size
  int x = 0, y = 0, w = 0, h = 0;     ///< the sub-image rectangle (OpenGL: from the lower left)
  TanRect fov{};
};

class GlComposer {
 public:
  /// Loads the GL entry points through `get_proc` and builds the program; null with
  /// `error` set when the context cannot (no OpenGL 3.3 core, a missing function).
  static std::unique_ptr<GlComposer> create(GlGetProcAddress get_proc, std::string& error);
  ~GlComposer();
  GlComposer(const GlComposer&) = delete;
  GlComposer& operator=(const GlComposer&) = delete;

  /// Draws the eye's output (`target`, w×h, covering field `out`) from its outer and
  /// inner views, blending across `blend_deg` inside the inner view's edge.
  /// srgb: the target's format is sRGB (encoded on write, blended linear). False when
  /// the framebuffer is incomplete.
  bool compose(const ComposeSource& outer, const ComposeSource& inner, std::uint32_t target, int w, int h,
               const TanRect& out, float blend_deg, bool srgb);
  /// The target's pixels, RGBA8, top row first (a capture; allocates).
  bool read(std::uint32_t target, int w, int h, std::vector<std::uint8_t>& rgba);

 private:
  GlComposer() = default;
  struct Gl;
  std::unique_ptr<Gl> gl_;
  std::uint32_t program_ = 0, vao_ = 0, fbo_ = 0, sampler_ = 0;
  int u_outer_tan_ = -1, u_outer_uv_ = -1, u_inner_tan_ = -1, u_inner_uv_ = -1, u_out_tan_ = -1, u_band_ = -1,
      u_out_size_ = -1, u_outer_tex_ = -1, u_inner_tex_ = -1;
};

}  // namespace foveal::openxr

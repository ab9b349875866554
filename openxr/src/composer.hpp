#pragma once
// The quad views' composer, one per session, on the app's graphics API: each eye's inner
// view blended over its upsampled outer view into a stereo image the layer submits
// (docs/openxr.md, "Composition"). GlComposer (gl_composer.cpp) and VkComposer
// (vk_composer.cpp) run the same shader (compose.glsl). Objects are made at the first
// frame; a frame allocates nothing.
#include <cstdint>
#include <vector>

#include "inset.hpp"

namespace foveal::openxr {

/// One source image: the image (and its layer, in an array swapchain), the rectangle the
/// app drew into, and its view's field.
struct ComposeSource {
  std::uint64_t image = 0;          ///< OpenGL: a texture name; Vulkan: a VkImage
  std::int64_t format = 0;          ///< the swapchain's format (Vulkan: a VkFormat; GL: unused)
  std::uint64_t serial = 0;         ///< differs for every new image, though its handle be reused (Vulkan's view cache)
  int image_w = 0, image_h = 0;     ///< the image's size
  int x = 0, y = 0, w = 0, h = 0;   ///< the sub-image rectangle (OpenGL: from the lower left; Vulkan: the upper left)
  TanRect fov{};
  std::uint32_t layer = 0;          ///< the sub-image's imageArrayIndex
  bool array = false;               ///< the swapchain's arraySize > 1 (OpenGL: a GL_TEXTURE_2D_ARRAY)
};

/// The image one eye's output goes to, all of it.
struct ComposeTarget {
  std::uint64_t image = 0;
  std::int64_t format = 0;          ///< GL internal format or VkFormat: sRGB formats are encoded on write
  std::uint64_t serial = 0;
  int w = 0, h = 0;
};

class Composer {
 public:
  virtual ~Composer() = default;
  /// Draws the eye's output (covering field `out`) from its outer and inner views,
  /// blending across `blend_deg` inside the inner view's edge. False: nothing was drawn.
  virtual bool compose(const ComposeSource& outer, const ComposeSource& inner, const ComposeTarget& target,
                       const TanRect& out, float blend_deg) = 0;
  /// The target's pixels, RGBA8, top row first (a capture; allocates and waits).
  virtual bool read(const ComposeTarget& target, std::vector<std::uint8_t>& rgba) = 0;
};

}  // namespace foveal::openxr

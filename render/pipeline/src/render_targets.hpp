#pragma once
// The compositor's framebuffers. Formats and bytes per pixel are in docs/rmfr.md.
#include <array>
#include <cstddef>

#include "foveal/render/gl_objects.hpp"

namespace foveal::render::detail {

/// A G-buffer (full size, with a depth buffer) or a transformed G-buffer (w×h, depth as
/// an R32F colour target written by the mapping pass). Texture units 0-4 in that order.
struct SurfaceTargets {
  gl::Texture albedo, normal, material, emissive, depth;
  gl::Framebuffer fbo;
  int width = 0, height = 0;

  static SurfaceTargets create(int width, int height, bool depth_as_color);
  /// albedo, normal, material, emissive, depth: the texture units' order.
  std::array<GLuint, 5> textures() const { return {albedo.id(), normal.id(), material.id(), emissive.id(), depth.id()}; }
  void bind_textures() const;
  std::size_t bytes() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 20; }
};

/// One colour target (the reduced lit buffer, the output) or a depth-only shadow map.
struct ColorTarget {
  gl::Texture texture;
  gl::Framebuffer fbo;
  int width = 0, height = 0;
  std::size_t bytes_per_pixel = 4;

  static ColorTarget create(int width, int height, GLenum format, bool linear_filter);
  static ColorTarget create_shadow(int size);
  std::size_t bytes() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * bytes_per_pixel; }
};

}  // namespace foveal::render::detail

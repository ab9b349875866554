#pragma once
// The compositor's framebuffers. Formats and bytes per pixel are in docs/rmfr.md.
#include <array>
#include <cstddef>
#include <optional>
#include <utility>

#include "foveal/render/gl_objects.hpp"

namespace foveal::render::detail {

/// When a target of have_w×have_h (if it exists) must be remade for w×h: the size to
/// allocate, or nothing when it fits. Exact sizes, or at least w×h with grow_only (the
/// layered methods' atlas changes shape with the fovea every frame, so it only grows).
inline std::optional<std::pair<int, int>> realloc_size(bool exists, int have_w, int have_h, int w, int h, bool grow_only) {
  const bool fits = exists && (grow_only ? (have_w >= w && have_h >= h) : (have_w == w && have_h == h));
  if (fits) return std::nullopt;
  if (grow_only && exists) return std::pair{w > have_w ? w : have_w, h > have_h ? h : have_h};
  return std::pair{w, h};
}

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

/// The visibility pipeline's full-resolution target: per pixel the nearest draw + 1 and
/// triangle (RG32UI, 0 = nothing) and the depth (D32F). Texture units 5 and 6.
struct VisibilityTarget {
  gl::Texture ids, depth;
  gl::Framebuffer fbo;
  int width = 0, height = 0;

  static VisibilityTarget create(int width, int height);
  std::size_t bytes() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 12; }
};

/// Per material slot, the tiles of a buffer that hold the material and the indirect draw
/// of them (layout in shaders/common/material_tiles.glsl): 16 bytes of command and room
/// for every tile, per slot; `empty` holds the commands before any tile is counted (a
/// quad per instance, no instances), copied over `commands` at each frame's start.
struct MaterialTiles {
  gl::Buffer commands, empty, lists;
  int across = 0, down = 0;
  std::size_t slots = 0;

  static MaterialTiles create(int width, int height, int tile, std::size_t slots);
  std::size_t count() const { return static_cast<std::size_t>(across) * static_cast<std::size_t>(down); }
  std::size_t bytes() const { return slots * (32 + count() * 4); }
};

/// What the visibility pipeline's material pass writes: a SurfaceTargets (depth as a
/// colour target) plus a D32F depth attachment that holds each texel's material for the
/// per-material passes (shaders/classify.frag), and its tile lists (made for the scene's
/// material count on first use).
struct MaterialSurface {
  SurfaceTargets surface;
  gl::Texture material_depth;
  MaterialTiles tiles;

  static MaterialSurface create(int width, int height);
  int width() const { return surface.width; }
  int height() const { return surface.height; }
  std::size_t bytes() const {
    return surface.bytes() + static_cast<std::size_t>(width()) * static_cast<std::size_t>(height()) * 4 + tiles.bytes();
  }
};

}  // namespace foveal::render::detail

#pragma once
// The compositor's framebuffers. Formats and bytes per pixel are in docs/rmfr.md.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

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

/// What a scene's G-buffer holds: the core targets (albedo, normal, material, emissive:
/// locations and units 0-3; depth 4) and one target per material feature its materials
/// use (MaterialFeature), at locations 5, 6, ... and, for the passes that read them,
/// texture units 8, 9, .... A plain metal-rough scene has no feature target.
struct SurfaceLayout {
  struct Target {
    unsigned feature;  ///< MaterialFeature
    const char* name;  ///< "clearcoat": the shader's FEATURE_CLEARCOAT, CLEARCOAT_LOCATION, CLEARCOAT_UNIT
    GLenum format;
    std::size_t bytes_per_pixel;
  };
  unsigned features = 0;
  std::vector<Target> targets;  ///< the feature targets, in location order
  /// Features of the forward pass alone (transmission): a shader define, no target.
  std::vector<const char*> forward;

  /// The layout of `features`; `features` of the result says which it holds: at most
  /// kMaxTargets feature targets (GL 4.5 promises 8 colour attachments: 4 core, the
  /// reduced buffers' depth, 3 more), in the order clearcoat, specular, sheen,
  /// anisotropy, iridescence; a scene with more is drawn without the rest (the caller warns).
  static SurfaceLayout for_features(unsigned features);
  static constexpr std::size_t kCoreBytesPerPixel = 20;  ///< the core targets and depth
  static constexpr std::size_t kMaxTargets = 3;
  static constexpr GLuint kFirstLocation = 5, kFirstUnit = 8;
  std::size_t bytes_per_pixel() const;
  /// The shader defines of the features: FEATURE_X, X_LOCATION and X_UNIT per target,
  /// FEATURE_X for a forward feature.
  std::string defines() const;
  /// "metal-rough" plus "+name" per feature: the shader variant's name.
  std::string variant_name() const;
};

/// A G-buffer (full size, with a depth buffer) or a transformed G-buffer (w×h, depth as
/// an R32F colour target written by the mapping pass), in `layout`.
struct SurfaceTargets {
  gl::Texture albedo, normal, material, emissive, depth;
  std::vector<gl::Texture> features;  ///< SurfaceLayout::targets
  gl::Framebuffer fbo;
  int width = 0, height = 0;
  std::size_t bytes_per_pixel = SurfaceLayout::kCoreBytesPerPixel;

  static SurfaceTargets create(int width, int height, bool depth_as_color, const SurfaceLayout& layout);
  /// albedo, normal, material, emissive, depth, then the feature targets: the order of
  /// the reduced buffers' attachments (foveal-rmfr maps texture k to attachment k).
  std::vector<GLuint> textures() const;
  /// Core targets on units 0-4, feature targets on units 8, 9, ....
  void bind_textures() const;
  std::size_t bytes() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * bytes_per_pixel; }
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

  static MaterialSurface create(int width, int height, const SurfaceLayout& layout);
  int width() const { return surface.width; }
  int height() const { return surface.height; }
  std::size_t bytes() const {
    return surface.bytes() + static_cast<std::size_t>(width()) * static_cast<std::size_t>(height()) * 4 + tiles.bytes();
  }
};

}  // namespace foveal::render::detail

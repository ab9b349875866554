#pragma once
// Per-tile light lists for the file's lights (docs/scenes.md, "Lights"): which lights can
// reach any point seen through each tile_px × tile_px tile of an eye's screen, from each
// light's range sphere projected to the screen, so the lighting pass loops over those
// only. A light without a range (or directional) is in every tile. CPU only.
#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>

#include "foveal/render/scene_types.hpp"

namespace foveal::render {

inline constexpr int kLightTilePx = 16;

struct LightTiles {
  int cols = 0, rows = 0, tile_px = kLightTilePx;
  /// cols × rows (first light index, count) pairs, row-major from the bottom-left
  /// tile (GL's pixel order), then the light indices they point into.
  std::vector<std::uint32_t> data;
};

/// The screen rectangle, in pixels [x0, x1) × [y0, y1) from the bottom left, that a
/// sphere may cover through `view_proj` on a width × height screen: the whole screen when
/// it reaches behind the near plane; empty (x0 >= x1) when it is off screen.
glm::ivec4 sphere_screen_rect(glm::vec3 centre, float radius, const glm::mat4& view_proj, int width, int height);

/// Lists for the first `count` of `lights` on a width × height eye.
LightTiles build_light_tiles(const std::vector<PunctualLight>& lights, std::size_t count, const glm::mat4& view_proj, int width,
                             int height, int tile_px = kLightTilePx);

}  // namespace foveal::render

#include "foveal/render/light_tiles.hpp"

#include <algorithm>
#include <cmath>

namespace foveal::render {

glm::ivec4 sphere_screen_rect(glm::vec3 c, float r, const glm::mat4& view_proj, int width, int height) {
  const glm::ivec4 all(0, 0, width, height);
  // The sphere's bounding box: its projection holds the sphere's when every corner is in
  // front of the eye (a convex hull projects onto the hull of its corners).
  float x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (int k = 0; k < 8; ++k) {
    const glm::vec3 p = c + r * glm::vec3((k & 1) ? 1 : -1, (k & 2) ? 1 : -1, (k & 4) ? 1 : -1);
    const glm::vec4 q = view_proj * glm::vec4(p, 1.0f);
    if (!(q.w > 1e-6f) || q.z < -q.w) return all;  // behind the eye or the near plane
    x0 = std::min(x0, q.x / q.w), x1 = std::max(x1, q.x / q.w);
    y0 = std::min(y0, q.y / q.w), y1 = std::max(y1, q.y / q.w);
  }
  auto px = [](float ndc, int n) {
    return static_cast<int>(std::clamp(std::floor((ndc * 0.5f + 0.5f) * static_cast<float>(n)), -1.0f, static_cast<float>(n) + 1.0f));
  };
  // One pixel of margin on each side for the rounding of pixel centres.
  glm::ivec4 rect(px(x0, width) - 1, px(y0, height) - 1, px(x1, width) + 2, px(y1, height) + 2);
  rect = glm::ivec4(std::max(rect.x, 0), std::max(rect.y, 0), std::min(rect.z, width), std::min(rect.w, height));
  if (rect.x >= rect.z || rect.y >= rect.w) return glm::ivec4(0);
  return rect;
}

LightTiles build_light_tiles(const std::vector<PunctualLight>& lights, std::size_t count, const glm::mat4& view_proj, int width,
                             int height, int tile_px) {
  LightTiles t;
  t.tile_px = tile_px;
  t.cols = (width + tile_px - 1) / tile_px;
  t.rows = (height + tile_px - 1) / tile_px;
  const std::size_t tiles = static_cast<std::size_t>(t.cols) * static_cast<std::size_t>(t.rows);
  std::vector<std::vector<std::uint32_t>> lists(tiles);
  count = std::min(count, lights.size());
  for (std::size_t i = 0; i < count; ++i) {
    const PunctualLight& l = lights[i];
    glm::ivec4 rect(0, 0, width, height);
    if (l.type != PunctualLight::Type::directional && l.range > 0.0f)
      rect = sphere_screen_rect(l.position, l.range, view_proj, width, height);
    if (rect.x >= rect.z || rect.y >= rect.w) continue;
    for (int y = rect.y / tile_px; y <= (rect.w - 1) / tile_px; ++y)
      for (int x = rect.x / tile_px; x <= (rect.z - 1) / tile_px; ++x)
        lists[static_cast<std::size_t>(y) * static_cast<std::size_t>(t.cols) + static_cast<std::size_t>(x)].push_back(
            static_cast<std::uint32_t>(i));
  }
  t.data.resize(2 * tiles);
  for (std::size_t k = 0; k < tiles; ++k) {
    t.data[2 * k] = static_cast<std::uint32_t>(t.data.size());
    t.data[2 * k + 1] = static_cast<std::uint32_t>(lists[k].size());
    t.data.insert(t.data.end(), lists[k].begin(), lists[k].end());
  }
  return t;
}

}  // namespace foveal::render

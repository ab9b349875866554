// Built-in screen-space patterns: a repeating tile drawn over each eye's viewport,
// rotated about the viewport centre, sampled with mipmaps like any scene texture.
#include <cmath>
#include <cstdlib>
#include <random>

#include "scene_internal.hpp"

namespace foveal::render::detail {

namespace {

struct Tile {
  int size;
  std::vector<std::uint8_t> rgba;
};

Tile make_tile(Pattern::Kind kind) {
  Tile t{kind == Pattern::Kind::noise ? 256 : kind == Pattern::Kind::checker ? 32 : 8, {}};
  const int n = t.size;
  t.rgba.assign(static_cast<std::size_t>(n * n * 4), 255);
  std::mt19937 rng(12345);  // fixed: golden images depend on it
  std::uniform_int_distribution<int> value(0, 255);
  std::vector<float> grid(16 * 16 * 3);
  for (float& g : grid) g = static_cast<float>(value(rng)) / 255.0f;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      std::uint8_t* p = &t.rgba[static_cast<std::size_t>((y * n + x) * 4)];
      switch (kind) {
        case Pattern::Kind::checker: {
          const bool on = ((x / 16) + (y / 16)) % 2 == 0;
          p[0] = p[1] = p[2] = on ? 230 : 25;
          break;
        }
        case Pattern::Kind::stripes_h: p[0] = p[1] = p[2] = (y / 4) % 2 ? 230 : 25; break;
        case Pattern::Kind::stripes_v: p[0] = p[1] = p[2] = (x / 4) % 2 ? 230 : 25; break;
        case Pattern::Kind::noise: {
          // Smooth value noise on a 16x16 periodic grid: detail at every scale.
          const float gx = static_cast<float>(x) * 16.0f / static_cast<float>(n), gy = static_cast<float>(y) * 16.0f / static_cast<float>(n);
          const int x0 = static_cast<int>(gx), y0 = static_cast<int>(gy);
          const float fx = gx - static_cast<float>(x0), fy = gy - static_cast<float>(y0);
          const float sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
          for (int c = 0; c < 3; ++c) {
            auto g = [&](int i, int j) { return grid[static_cast<std::size_t>((((j & 15) * 16) + (i & 15)) * 3 + c)]; };
            const float v = (g(x0, y0) * (1 - sx) + g(x0 + 1, y0) * sx) * (1 - sy) + (g(x0, y0 + 1) * (1 - sx) + g(x0 + 1, y0 + 1) * sx) * sy;
            const float fine = ((x / 2 + y / 2) % 2) ? 0.12f : -0.12f;  // 2-px texture detail
            p[c] = static_cast<std::uint8_t>(std::lround(std::fmin(std::fmax(v + fine, 0.0f), 1.0f) * 255.0f));
          }
          break;
        }
      }
    }
  return t;
}

}  // namespace

Result<Scene> make_pattern_scene(const std::string& spec) {
  std::string name = spec.substr(std::string("pattern:").size());
  float angle = 0.0f;
  if (const auto at = name.find('@'); at != std::string::npos) {
    const std::string a = name.substr(at + 1);
    char* end = nullptr;
    angle = std::strtof(a.c_str(), &end);
    if (a.empty() || *end != '\0' || !std::isfinite(angle))
      return bad_input(spec + ": expected pattern:NAME@DEGREES, got angle '" + a + "'");
    name.resize(at);
  }
  Pattern p;
  if (name == "checker") p.kind = Pattern::Kind::checker;
  else if (name == "stripes-h") p.kind = Pattern::Kind::stripes_h;
  else if (name == "stripes-v") p.kind = Pattern::Kind::stripes_v;
  else if (name == "noise") p.kind = Pattern::Kind::noise;
  else return bad_input(spec + ": unknown pattern '" + name + "' (checker, stripes-h, stripes-v, noise; add @DEGREES to rotate)");
  p.angle_deg = angle;
  Scene s;
  s.name = spec;
  const Tile tile = make_tile(p.kind);
  p.tile_px = static_cast<float>(tile.size);
  p.texture = upload_rgba8(tile.rgba.data(), tile.size, tile.size, true, GL_REPEAT, GL_REPEAT, &s.texture_bytes);
  s.pattern = std::move(p);
  s.view.source = "screen space";
  return s;
}

}  // namespace foveal::render::detail

#pragma once
// Float planes and the Burt-Adelson Gaussian pyramid steps (5 taps, a = 0.4) FovVideoVDP
// decomposes luminance with (docs/metrics.md, "JOD").
#include <cstddef>
#include <vector>

namespace foveal::perception {

struct Plane {
  int width = 0, height = 0;
  std::vector<float> v;
  Plane() = default;
  Plane(int w, int h) : width(w), height(h), v(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0.0f) {}
  float* row(int y) { return v.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width); }
  const float* row(int y) const { return v.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width); }
};

/// Blur with [0.05 0.25 0.4 0.25 0.05] along x and y and keep every second sample:
/// ceil(w/2) × ceil(h/2); edges mirrored about the border (x[-1] = x[0], x[-2] = x[1]).
Plane pyramid_reduce(const Plane& in);
/// Upsample `coarse` to w × h (w ≤ 2·coarse.width, h ≤ 2·coarse.height) by zero insertion
/// and the same kernel doubled; coarse samples past the end repeat the last one.
Plane pyramid_expand(const Plane& coarse, int w, int h);

}  // namespace foveal::perception

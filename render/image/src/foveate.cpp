#include "foveal/image/foveate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "foveal/rmfr_mapping.hpp"

namespace foveal::image {

using namespace foveal::rmfr;  // the one RMFR mapping (foveal/rmfr_mapping.hpp)

namespace {

// Summed-area table of the image as a piecewise-constant function: integral() of any
// real rectangle is exact (the SAT is bilinear between its integer samples).
class AreaIntegral {
 public:
  explicit AreaIntegral(const Image& img) : w_(img.width), h_(img.height), s_(std::size_t(w_ + 1) * std::size_t(h_ + 1)) {
    for (int y = 0; y < h_; ++y) {
      std::array<double, 4> row{};
      for (int x = 0; x < w_; ++x) {
        for (int c = 0; c < 4; ++c) row[c] += img.at(x, y)[c];
        auto& cell = at(x + 1, y + 1);
        const auto& up = at(x + 1, y);
        for (int c = 0; c < 4; ++c) cell[c] = up[c] + row[c];
      }
    }
  }
  /// Sum over [x0, x1) × [y0, y1) in pixel units.
  std::array<double, 4> integral(double x0, double y0, double x1, double y1) const {
    auto a = sample(x1, y1), b = sample(x0, y1), c = sample(x1, y0), d = sample(x0, y0);
    for (int i = 0; i < 4; ++i) a[i] = a[i] - b[i] - c[i] + d[i];
    return a;
  }

 private:
  std::array<double, 4>& at(int x, int y) { return s_[std::size_t(y) * std::size_t(w_ + 1) + std::size_t(x)]; }
  const std::array<double, 4>& at(int x, int y) const { return s_[std::size_t(y) * std::size_t(w_ + 1) + std::size_t(x)]; }
  std::array<double, 4> sample(double x, double y) const {
    x = std::clamp(x, 0.0, double(w_));
    y = std::clamp(y, 0.0, double(h_));
    const int ix = std::min(int(x), w_ - 1), iy = std::min(int(y), h_ - 1);
    const double fx = x - ix, fy = y - iy;
    std::array<double, 4> r{};
    for (int c = 0; c < 4; ++c)
      r[c] = (at(ix, iy)[c] * (1 - fx) + at(ix + 1, iy)[c] * fx) * (1 - fy) +
             (at(ix, iy + 1)[c] * (1 - fx) + at(ix + 1, iy + 1)[c] * fx) * fy;
    return r;
  }
  int w_, h_;
  std::vector<std::array<double, 4>> s_;
};

std::uint8_t to_byte(double v) { return static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L)); }

// Edges of the buffer's cells on the screen, in screen pixels: cell i spans
// [edges[i], edges[i+1]).
std::vector<double> cell_edges(int buffer, int screen, double c, double f) {
  std::vector<double> e(std::size_t(buffer) + 1);
  for (int i = 0; i <= buffer; ++i) e[std::size_t(i)] = rmfr_inverse(double(i) / buffer, c, f) * screen;
  return e;
}

}  // namespace

Result<FoveateResult> foveate(const Image& in, const FoveateParams& p) {
  if (in.empty()) return bad_input("foveate: empty input image");
  if (!std::isfinite(p.sigma) || p.sigma < 1.0) return bad_input("foveate: sigma must be a number >= 1");
  if (!std::isfinite(p.fx) || !std::isfinite(p.fy) || p.fx <= 0 || p.fy <= 0)
    return bad_input("foveate: fx and fy must be numbers > 0");
  // sigma = 1 is the identity: no reduction, no warp (see docs/rmfr.md).
  const double cx = sanitize_fovea(p.fovea_x), cy = sanitize_fovea(p.fovea_y);
  const double fx = rmfr_effective_f(p.fx, p.sigma, cx), fy = rmfr_effective_f(p.fy, p.sigma, cy);
  const int w = rmfr_buffer_size(in.width, p.sigma), h = rmfr_buffer_size(in.height, p.sigma);

  FoveateResult r{Image(w, h), Image(in.width, in.height)};
  const AreaIntegral sat(in);
  const auto ex = cell_edges(w, in.width, cx, fx), ey = cell_edges(h, in.height, cy, fy);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      double x0 = ex[std::size_t(i)], x1 = ex[std::size_t(i) + 1], y0 = ey[std::size_t(j)], y1 = ey[std::size_t(j) + 1];
      // A cell narrower than a pixel (dense sampling near the fovea) takes the pixel
      // under its centre: widen it to one pixel around its centre.
      if (x1 - x0 < 1) x0 = (x0 + x1 - 1) / 2, x1 = x0 + 1;
      if (y1 - y0 < 1) y0 = (y0 + y1 - 1) / 2, y1 = y0 + 1;
      const auto s = sat.integral(x0, y0, x1, y1);
      const double area = (x1 - x0) * (y1 - y0);
      for (int c = 0; c < 4; ++c) r.reduced.at(i, j)[c] = to_byte(s[std::size_t(c)] / area);
    }

  // Inverse: bilinear in the reduced buffer at the forward-mapped pixel centre.
  std::vector<double> ux(std::size_t(in.width)), uy(std::size_t(in.height));
  for (int x = 0; x < in.width; ++x) ux[std::size_t(x)] = rmfr_forward((x + 0.5) / in.width, cx, fx) * w - 0.5;
  for (int y = 0; y < in.height; ++y) uy[std::size_t(y)] = rmfr_forward((y + 0.5) / in.height, cy, fy) * h - 0.5;
  for (int y = 0; y < in.height; ++y) {
    const double v = std::clamp(uy[std::size_t(y)], 0.0, double(h - 1));
    const int y0 = std::min(int(v), h - 1), y1 = std::min(y0 + 1, h - 1);
    const double ty = v - y0;
    for (int x = 0; x < in.width; ++x) {
      const double u = std::clamp(ux[std::size_t(x)], 0.0, double(w - 1));
      const int x0 = std::min(int(u), w - 1), x1 = std::min(x0 + 1, w - 1);
      const double tx = u - x0;
      for (int c = 0; c < 4; ++c) {
        const double top = r.reduced.at(x0, y0)[c] * (1 - tx) + r.reduced.at(x1, y0)[c] * tx;
        const double bottom = r.reduced.at(x0, y1)[c] * (1 - tx) + r.reduced.at(x1, y1)[c] * tx;
        r.output.at(x, y)[c] = to_byte(top * (1 - ty) + bottom * ty);
      }
    }
  }
  return r;
}

}  // namespace foveal::image

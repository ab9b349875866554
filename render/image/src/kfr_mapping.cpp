#include "foveal/image/kfr_mapping.hpp"

#include <array>
#include <unordered_set>
#include <vector>

#include "foveal/rmfr_mapping.hpp"

namespace foveal::image {

using namespace foveal::rmfr;  // the one RMFR mapping (foveal/rmfr_mapping.hpp)

namespace {

constexpr double kTwoPi = 6.283185307179586;

// One eye's log-polar buffer: its size and, per texel, the screen pixel it samples, in
// GL's frame (origin bottom-left) like the compositor.
struct KfrBuffer {
  int w = 0, h = 0;
  double cx = 0, cy = 0, log_max = 1, alpha = 4;
  std::vector<int> source_x, source_y;  // texel (i, j) at j * w + i

  KfrBuffer(int W, int H, double sigma, double a, double fovea_x, double fovea_y)
      : w(rmfr_buffer_size(W, sigma)), h(rmfr_buffer_size(H, sigma)), alpha(a) {
    cx = sanitize_fovea(fovea_x) * W, cy = (1.0 - sanitize_fovea(fovea_y)) * H;
    log_max = kfr_log_max(W, H, cx, cy);
    source_x.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    source_y.resize(source_x.size());
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        const double r = kfr_radius((i + 0.5) / w, log_max, alpha), theta = kTwoPi * (j + 0.5) / h;
        const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + static_cast<std::size_t>(i);
        source_x[k] = std::clamp(static_cast<int>(std::floor(cx + r * std::cos(theta))), 0, W - 1);
        source_y[k] = std::clamp(static_cast<int>(std::floor(cy + r * std::sin(theta))), 0, H - 1);
      }
  }
};

float srgb_to_linear(std::uint8_t v) {
  const double c = v / 255.0;
  return static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

std::uint8_t linear_to_srgb(double c) {
  c = std::clamp(c, 0.0, 1.0);
  const double s = c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::lround(s * 255.0));
}

}  // namespace

Image simulate_kfr(const Image& full_eye, double sigma, double alpha, double fovea_x, double fovea_y) {
  const int W = full_eye.width, H = full_eye.height;
  Image out(W, H);
  if (full_eye.empty()) return out;
  const KfrBuffer b(W, H, sigma, alpha, fovea_x, fovea_y);
  std::array<float, 256> linear{};
  for (int v = 0; v < 256; ++v) linear[static_cast<std::size_t>(v)] = srgb_to_linear(static_cast<std::uint8_t>(v));
  // The lit buffer: each texel is the full frame's pixel at its source (image rows run down).
  auto texel = [&](int i, int j) {
    const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(b.w) + static_cast<std::size_t>(i);
    return full_eye.at(b.source_x[k], H - 1 - b.source_y[k]);
  };
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const double dx = x + 0.5 - b.cx, dy = y + 0.5 - b.cy;  // GL frame: row y is image row H-1-y
      const double u = kfr_column(std::hypot(dx, dy), b.log_max, b.alpha);
      double v = std::atan2(dy, dx) / kTwoPi;
      v -= std::floor(v);
      const double s = u * b.w - 0.5, t = v * b.h - 0.5;
      const int s0 = static_cast<int>(std::floor(s)), t0 = static_cast<int>(std::floor(t));
      const double fs = s - s0, ft = t - t0;
      const int i0 = std::clamp(s0, 0, b.w - 1), i1 = std::clamp(s0 + 1, 0, b.w - 1);
      const int j0 = ((t0 % b.h) + b.h) % b.h, j1 = (j0 + 1) % b.h;
      const std::uint8_t *p00 = texel(i0, j0), *p10 = texel(i1, j0), *p01 = texel(i0, j1), *p11 = texel(i1, j1);
      std::uint8_t* o = out.at(x, H - 1 - y);
      for (int c = 0; c < 3; ++c) {
        auto lin = [&](const std::uint8_t* p) { return static_cast<double>(linear[p[c]]); };
        const double bottom = lin(p00) + (lin(p10) - lin(p00)) * fs, top = lin(p01) + (lin(p11) - lin(p01)) * fs;
        o[c] = linear_to_srgb(bottom + (top - bottom) * ft);
      }
      o[3] = 255;
    }
  return out;
}

double kfr_distinct_fraction(int W, int H, double sigma, double alpha, double fovea_x, double fovea_y) {
  if (W < 1 || H < 1) return 0;
  const KfrBuffer b(W, H, sigma, alpha, fovea_x, fovea_y);
  std::unordered_set<long long> hit;
  for (std::size_t k = 0; k < b.source_x.size(); ++k) hit.insert(static_cast<long long>(b.source_y[k]) * W + b.source_x[k]);
  return static_cast<double>(hit.size()) / static_cast<double>(b.source_x.size());
}

}  // namespace foveal::image

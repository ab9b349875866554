#include "foveal/image/auto_f.hpp"

#include <chrono>
#include <cmath>
#include <vector>

#include "foveal/rmfr_mapping.hpp"

namespace foveal::image {

using namespace foveal::rmfr;  // the one RMFR mapping (foveal/rmfr_mapping.hpp)

namespace {

// Per-axis tables of the simulated pipeline: source pixel of each buffer texel, and the
// bilinear position in the buffer of each screen pixel.
struct AxisMap {
  std::vector<int> source;     // buffer texel -> screen pixel
  std::vector<int> lo, hi;     // screen pixel -> buffer texels
  std::vector<float> t;        // weight of hi
};

AxisMap axis_map(int screen, double sigma, double c, double f) {
  const int n = rmfr_buffer_size(screen, sigma);
  const double fe = rmfr_effective_f(f, sigma, c);
  AxisMap m;
  m.source.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    m.source[static_cast<std::size_t>(i)] = rmfr_source_pixel(i, n, screen, c, fe);
  m.lo.resize(static_cast<std::size_t>(screen));
  m.hi.resize(static_cast<std::size_t>(screen));
  m.t.resize(static_cast<std::size_t>(screen));
  for (int x = 0; x < screen; ++x) {
    const double u = std::clamp(rmfr_forward((x + 0.5) / screen, c, fe) * n - 0.5, 0.0, double(n - 1));
    const int lo = std::min(static_cast<int>(u), n - 1);
    m.lo[static_cast<std::size_t>(x)] = lo;
    m.hi[static_cast<std::size_t>(x)] = std::min(lo + 1, n - 1);
    m.t[static_cast<std::size_t>(x)] = static_cast<float>(u - lo);
  }
  return m;
}

// The search sums the error over every second row and column (each of those pixels
// predicted exactly): plenty to rank candidate f, 4× cheaper. The reported prediction
// uses every pixel.
constexpr int kSearchStride = 2;

// Σ w²·err² over one eye of the predicted image (err² the mean over R, G, B), without
// building the image.
double weighted_error(const Image& eye, const std::vector<double>& w2, double sigma, double fx, double fy, double cx,
                      double cy, int stride) {
  const AxisMap mx = axis_map(eye.width, sigma, cx, fx), my = axis_map(eye.height, sigma, cy, fy);
  double sum = 0;
  for (int y = 0; y < eye.height; y += stride) {
    const std::size_t yy = static_cast<std::size_t>(y);
    const int r0 = my.source[static_cast<std::size_t>(my.lo[yy])], r1 = my.source[static_cast<std::size_t>(my.hi[yy])];
    const float ty = my.t[yy];
    for (int x = 0; x < eye.width; x += stride) {
      const std::size_t xx = static_cast<std::size_t>(x);
      const int c0 = mx.source[static_cast<std::size_t>(mx.lo[xx])], c1 = mx.source[static_cast<std::size_t>(mx.hi[xx])];
      const float tx = mx.t[xx];
      const std::uint8_t *a = eye.at(c0, r0), *b = eye.at(c1, r0), *c = eye.at(c0, r1), *d = eye.at(c1, r1);
      const std::uint8_t* ref = eye.at(x, y);
      double e2 = 0;
      for (int k = 0; k < 3; ++k) {
        const float top = a[k] + (b[k] - a[k]) * tx, bottom = c[k] + (d[k] - c[k]) * tx;
        // The GPU stores the lit buffer in 8 bits: round like it.
        const double v = std::round(top + (bottom - top) * ty);
        const double diff = v - ref[k];
        e2 += diff * diff;
      }
      sum += w2[yy * static_cast<std::size_t>(eye.width) + xx] * e2 / 3.0;
    }
  }
  return sum;
}

std::vector<double> weights_squared(int w, int h, double fovea_x, double fovea_y, double ppd) {
  const double f = focal_length_px(ppd);
  const double gx = fovea_x * w - w / 2.0, gy = fovea_y * h - h / 2.0;
  std::vector<double> out(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double c = foveation_cutoff_cpd(eccentricity_deg(x + 0.5 - w / 2.0, y + 0.5 - h / 2.0, gx, gy, f), ppd);
      out[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)] = c * c;
    }
  return out;
}

}  // namespace

Image simulate_rmfr(const Image& full_eye, double sigma, double fx, double fy, double fovea_x, double fovea_y) {
  const AxisMap mx = axis_map(full_eye.width, sigma, fovea_x, fx), my = axis_map(full_eye.height, sigma, fovea_y, fy);
  Image out(full_eye.width, full_eye.height);
  for (int y = 0; y < out.height; ++y) {
    const std::size_t yy = static_cast<std::size_t>(y);
    const int r0 = my.source[static_cast<std::size_t>(my.lo[yy])], r1 = my.source[static_cast<std::size_t>(my.hi[yy])];
    for (int x = 0; x < out.width; ++x) {
      const std::size_t xx = static_cast<std::size_t>(x);
      const int c0 = mx.source[static_cast<std::size_t>(mx.lo[xx])], c1 = mx.source[static_cast<std::size_t>(mx.hi[xx])];
      for (int k = 0; k < 4; ++k) {
        const float top = full_eye.at(c0, r0)[k] + (full_eye.at(c1, r0)[k] - full_eye.at(c0, r0)[k]) * mx.t[xx];
        const float bottom = full_eye.at(c0, r1)[k] + (full_eye.at(c1, r1)[k] - full_eye.at(c0, r1)[k]) * mx.t[xx];
        out.at(x, y)[k] = static_cast<std::uint8_t>(std::lround(top + (bottom - top) * my.t[yy]));
      }
    }
  }
  return out;
}

Result<AutoF> estimate_rmfr_f(const Image& full, std::array<double, 2> sigma, const MetricsOptions& mo) {
  if (full.empty() || full.width % 2) return bad_input("automatic f: expected a side-by-side frame with an even width");
  for (double s : sigma)
    if (!std::isfinite(s) || s < 1) return bad_input("automatic f: sigma must be >= 1");
  const auto start = std::chrono::steady_clock::now();
  const int w = full.width / 2;
  const Image eyes[2] = {crop(full, Rect{0, 0, w, full.height}), crop(full, Rect{w, 0, w, full.height})};
  const NormPoint foveae[2] = {mo.fovea, mo.fovea_right};
  std::vector<double> w2[2];
  double weight_total[2] = {0, 0};  // over the search's pixels, over every pixel
  for (int e = 0; e < 2; ++e) {
    w2[e] = weights_squared(w, full.height, foveae[e].x, foveae[e].y, mo.ppd);
    for (int y = 0; y < full.height; ++y)
      for (int x = 0; x < w; ++x) {
        const double v = w2[e][static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)];
        weight_total[1] += v;
        if (y % kSearchStride == 0 && x % kSearchStride == 0) weight_total[0] += v;
      }
  }
  AutoF r;
  auto fmse = [&](double fx, double fy, int stride = kSearchStride) {
    ++r.evaluations;
    double s = 0;
    for (int e = 0; e < 2; ++e)
      s += weighted_error(eyes[e], w2[e], sigma[static_cast<std::size_t>(e)], fx, fy, foveae[e].x, foveae[e].y, stride);
    return s / weight_total[stride == 1 ? 1 : 0];
  };
  // Coordinate search on log f: golden-section along x, then y, twice.
  const double lo = std::log(0.05), hi = std::log(1.0), g = (std::sqrt(5.0) - 1) / 2;
  double lx = std::log(0.3), ly = std::log(0.3);
  for (int round = 0; round < 2; ++round)
    for (int axis = 0; axis < 2; ++axis) {
      double a = lo, b = hi;
      auto eval = [&](double v) { return axis == 0 ? fmse(std::exp(v), std::exp(ly)) : fmse(std::exp(lx), std::exp(v)); };
      double c = b - g * (b - a), d = a + g * (b - a), fc = eval(c), fd = eval(d);
      for (int i = 0; i < 7; ++i) {  // the bracket shrinks to 3% of ln(20): f within ±5%
        if (fc < fd) {  // the minimum lies in [a, d]
          b = d, d = c, fd = fc;
          c = b - g * (b - a), fc = eval(c);
        } else {        // in [c, b]
          a = c, c = d, fc = fd;
          d = a + g * (b - a), fd = eval(d);
        }
      }
      (axis == 0 ? lx : ly) = 0.5 * (a + b);
    }
  r.fx = std::exp(lx);
  r.fy = std::exp(ly);
  const double m = fmse(r.fx, r.fy, 1);
  r.predicted_fpsnr_db = m > 0 ? 10 * std::log10(255.0 * 255.0 / m) : INFINITY;
  r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace foveal::image

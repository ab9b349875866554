#include "foveal/image/metrics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace foveal::image {

namespace {

constexpr int kSsimRadius = 5;  // scipy's int(truncate 3.5 * sigma 1.5 + 0.5), as scikit-image
constexpr int kSsimWin = 2 * kSsimRadius + 1;
constexpr double kSsimSigma = 1.5;
constexpr double kL = 255.0;
constexpr double kC1 = (0.01 * kL) * (0.01 * kL);
constexpr double kC2 = (0.03 * kL) * (0.03 * kL);

std::array<double, kSsimWin> gaussian_window() {
  std::array<double, kSsimWin> w{};
  double sum = 0;
  for (int k = 0; k < kSsimWin; ++k) {
    const double x = k - kSsimRadius;
    w[static_cast<std::size_t>(k)] = std::exp(-0.5 * x * x / (kSsimSigma * kSsimSigma));
    sum += w[static_cast<std::size_t>(k)];
  }
  for (double& v : w) v /= sum;
  return w;
}

std::string size_str(const Image& img) { return std::to_string(img.width) + "x" + std::to_string(img.height); }

// Mean SSIM over the valid window positions inside `r`. The filter is separable: each
// input row is filtered horizontally into a ring of 11 rows, and every output row is the
// vertical filter over that ring, so memory stays O(width) and the loops run over
// contiguous arrays. Identical inputs go through identical arithmetic, so they give
// exactly 1.
template <class Value>
double mean_ssim(const Image& a, const Image& b, Rect r, Value value) {
  const auto w = gaussian_window();
  const auto W = static_cast<std::size_t>(r.w);
  const auto OW = W - (kSsimWin - 1);
  constexpr std::size_t kQ = 5;  // x, y, x², y², x·y
  std::vector<double> src(kQ * W), ring(kQ * kSsimWin * OW), acc(kQ * OW);
  double total = 0;
  for (int y = 0; y < r.h; ++y) {
    double *sx = src.data(), *sy = sx + W, *sxx = sy + W, *syy = sxx + W, *sxy = syy + W;
    const std::uint8_t *pa = a.at(r.x, r.y + y), *pb = b.at(r.x, r.y + y);
    for (std::size_t i = 0; i < W; ++i) {
      const double p = value(pa + 4 * i), q = value(pb + 4 * i);
      sx[i] = p;
      sy[i] = q;
      sxx[i] = p * p;
      syy[i] = q * q;
      sxy[i] = p * q;
    }
    double* slot = ring.data() + static_cast<std::size_t>(y % kSsimWin) * kQ * OW;
    for (std::size_t q = 0; q < kQ; ++q) {
      const double* in = src.data() + q * W;
      double* out = slot + q * OW;
      for (std::size_t i = 0; i < OW; ++i) out[i] = w[0] * in[i];
      for (std::size_t k = 1; k < kSsimWin; ++k) {
        const double wk = w[k];
        const double* ink = in + k;
        for (std::size_t i = 0; i < OW; ++i) out[i] += wk * ink[i];
      }
    }
    if (y < kSsimWin - 1) continue;
    // Rows y-10 .. y are in the ring; filter them vertically.
    for (std::size_t k = 0; k < kSsimWin; ++k) {
      const double wk = w[k];
      const double* row = ring.data() + static_cast<std::size_t>((y - (kSsimWin - 1) + static_cast<int>(k)) % kSsimWin) * kQ * OW;
      if (k == 0)
        for (std::size_t i = 0; i < kQ * OW; ++i) acc[i] = wk * row[i];
      else
        for (std::size_t i = 0; i < kQ * OW; ++i) acc[i] += wk * row[i];
    }
    const double *mx = acc.data(), *my = mx + OW, *exx = my + OW, *eyy = exx + OW, *exy = eyy + OW;
    double row_sum = 0;
    for (std::size_t i = 0; i < OW; ++i) {
      // Population (co)variances: use_sample_covariance=False in scikit-image.
      const double vx = exx[i] - mx[i] * mx[i], vy = eyy[i] - my[i] * my[i], vxy = exy[i] - mx[i] * my[i];
      row_sum += ((2 * mx[i] * my[i] + kC1) * (2 * vxy + kC2)) / ((mx[i] * mx[i] + my[i] * my[i] + kC1) * (vx + vy + kC2));
    }
    total += row_sum;
  }
  return total / (static_cast<double>(OW) * static_cast<double>(r.h - (kSsimWin - 1)));
}

double psnr_from_mse(double mse) {
  if (mse == 0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(kL * kL / mse);
}

Status check_pair(const Image& ref, const Image& test) {
  if (ref.empty()) return bad_input("the reference image is empty");
  if (test.empty()) return bad_input("the test image is empty");
  if (ref.width != test.width || ref.height != test.height)
    return bad_input("image sizes differ: reference " + size_str(ref) + ", test " + size_str(test));
  return {};
}

Status check_fovea(NormPoint p, const char* what) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || p.x < 0 || p.x > 1 || p.y < 0 || p.y > 1)
    return bad_input(std::string(what) + ": X and Y must be finite and lie in [0,1], got " + std::to_string(p.x) + "," +
                     std::to_string(p.y));
  return {};
}

Status check_ppd(double ppd) {
  if (!std::isfinite(ppd) || ppd <= 0) return bad_input("ppd must be a finite number > 0, got " + std::to_string(ppd));
  return {};
}

// PSNR, FPSNR and SSIM of the region `r` with its own centre and the fovea at the
// normalised point `g` of the region. Inputs already checked.
Result<Metrics> region_metrics(const Image& ref, const Image& test, Rect r, NormPoint g, const MetricsOptions& opt) {
  auto s = ssim(ref, test, r, opt.ssim_channels);
  if (!s) return s.error();
  const double f = focal_length_px(opt.ppd);
  const double cx = 0.5 * r.w, cy = 0.5 * r.h;
  const double gx = g.x * r.w - cx, gy = g.y * r.h - cy;
  const double g_norm2 = gx * gx + gy * gy + f * f;
  // Inside the eccentricity where f_c reaches the Nyquist cap every weight is the cap:
  // a cosine comparison spares the acos there. Outside, acos is precise enough (the
  // angle is not near 0 unless no pixel is capped, and then 1e-6° does not matter).
  const double cap = 0.5 * opt.ppd;
  const double e_cap_deg = kFoveaE2 * std::log(1.0 / kFoveaCT0) / (kFoveaAlpha * cap) - kFoveaE2;
  const double cos_cap = e_cap_deg > 0 ? std::cos(e_cap_deg * std::numbers::pi / 180.0) : 2.0;
  double sum_err = 0, sum_w2 = 0, sum_w2_err = 0;
  for (int y = 0; y < r.h; ++y) {
    const double py = y + 0.5 - cy;  // pixel centres (docs/conventions.md)
    double row_err = 0, row_w2 = 0, row_w2_err = 0;
    for (int x = 0; x < r.w; ++x) {
      const std::uint8_t *p = ref.at(r.x + x, r.y + y), *q = test.at(r.x + x, r.y + y);
      double e2 = 0;
      for (int c = 0; c < 3; ++c) {
        const double d = double(p[c]) - double(q[c]);
        e2 += d * d;
      }
      const double px = x + 0.5 - cx;
      const double cos_e = (px * gx + py * gy + f * f) / std::sqrt((px * px + py * py + f * f) * g_norm2);
      double w2 = cap * cap;
      if (cos_e < cos_cap) {
        const double wc = foveation_cutoff_cpd(std::acos(std::max(cos_e, -1.0)) * (180.0 / std::numbers::pi), opt.ppd);
        w2 = wc * wc;
      }
      row_err += e2;
      row_w2 += w2;
      row_w2_err += w2 * e2;
    }
    sum_err += row_err;
    sum_w2 += row_w2;
    sum_w2_err += row_w2_err;
  }
  Metrics m;
  m.pixels = static_cast<std::size_t>(r.w) * static_cast<std::size_t>(r.h);
  m.mse = sum_err / (3.0 * static_cast<double>(m.pixels));
  m.fmse = sum_w2_err / (3.0 * sum_w2);
  m.weight_sum = sum_w2;
  m.psnr_db = psnr_from_mse(m.mse);
  m.fpsnr_db = psnr_from_mse(m.fmse);
  m.ssim = *s;
  return m;
}

}  // namespace

double focal_length_px(double ppd) { return ppd * 180.0 / std::numbers::pi; }

double eccentricity_deg(double px, double py, double gx, double gy, double f_px) {
  // The angle between (px, py, f) and (gx, gy, f): the same as acos of the normalised dot
  // product (DESIGN.md section 3), but atan2 keeps its precision near 0.
  const double cx = py * f_px - f_px * gy, cy = f_px * gx - px * f_px, cz = px * gy - py * gx;
  const double dot = px * gx + py * gy + f_px * f_px;
  return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), dot) * (180.0 / std::numbers::pi);
}

double foveation_cutoff_cpd(double ecc_deg, double ppd) {
  const double fc = kFoveaE2 * std::log(1.0 / kFoveaCT0) / (kFoveaAlpha * (ecc_deg + kFoveaE2));
  return std::min(fc, 0.5 * ppd);
}

Result<double> ssim(const Image& a, const Image& b, Rect r, SsimChannels ch) {
  if (a.width != b.width || a.height != b.height)
    return bad_input("SSIM: image sizes differ: " + size_str(a) + " and " + size_str(b));
  if (r.x < 0 || r.y < 0 || r.w <= 0 || r.h <= 0 || r.x + r.w > a.width || r.y + r.h > a.height)
    return bad_input("SSIM: region outside the " + size_str(a) + " image");
  if (r.w < kSsimWin || r.h < kSsimWin)
    return bad_input("SSIM: " + std::to_string(r.w) + "x" + std::to_string(r.h) + " is smaller than the 11x11 window");
  if (ch == SsimChannels::luma)
    return mean_ssim(a, b, r, [](const std::uint8_t* p) { return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2]; });
  double sum = 0;
  for (int c = 0; c < 3; ++c) sum += mean_ssim(a, b, r, [c](const std::uint8_t* p) { return double(p[c]); });
  return sum / 3.0;
}

Result<double> ssim(const Image& a, const Image& b, SsimChannels ch) { return ssim(a, b, Rect{0, 0, a.width, a.height}, ch); }

Result<Metrics> compute_metrics(const Image& ref, const Image& test, const MetricsOptions& opt) {
  if (Status s = check_pair(ref, test); !s) return s.error();
  if (Status s = check_ppd(opt.ppd); !s) return s.error();
  if (Status s = check_fovea(opt.fovea, "fovea"); !s) return s.error();
  return region_metrics(ref, test, Rect{0, 0, ref.width, ref.height}, opt.fovea, opt);
}

Result<StereoMetrics> compute_stereo_metrics(const Image& ref, const Image& test, const MetricsOptions& opt) {
  if (Status s = check_pair(ref, test); !s) return s.error();
  if (ref.width % 2 != 0)
    return bad_input("a side-by-side stereo frame needs an even width, got " + size_str(ref));
  if (Status s = check_ppd(opt.ppd); !s) return s.error();
  if (Status s = check_fovea(opt.fovea, "left fovea"); !s) return s.error();
  if (Status s = check_fovea(opt.fovea_right, "right fovea"); !s) return s.error();
  const int half = ref.width / 2;
  auto left = region_metrics(ref, test, Rect{0, 0, half, ref.height}, opt.fovea, opt);
  if (!left) return left.error();
  auto right = region_metrics(ref, test, Rect{half, 0, half, ref.height}, opt.fovea_right, opt);
  if (!right) return right.error();
  StereoMetrics out{*left, *right, {}};
  Metrics& c = out.combined;
  c.pixels = left->pixels + right->pixels;
  c.mse = (left->mse * double(left->pixels) + right->mse * double(right->pixels)) / double(c.pixels);
  c.weight_sum = left->weight_sum + right->weight_sum;
  c.fmse = (left->fmse * left->weight_sum + right->fmse * right->weight_sum) / c.weight_sum;
  c.psnr_db = psnr_from_mse(c.mse);
  c.fpsnr_db = psnr_from_mse(c.fmse);
  c.ssim = 0.5 * (left->ssim + right->ssim);
  return out;
}

}  // namespace foveal::image

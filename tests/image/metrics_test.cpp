// PSNR, SSIM and FPSNR (docs/metrics.md): analytic values, a brute-force SSIM, the
// foveation weights, the stereo split and the errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "foveal/image/metrics.hpp"

using namespace foveal::image;

namespace {

constexpr double kC1 = 6.5025, kC2 = 58.5225;  // (0.01·255)², (0.03·255)²

Image random_image(int w, int h, unsigned seed, int lo = 0, int hi = 255) {
  Image img(w, h);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> d(lo, hi);
  for (std::size_t i = 0; i < img.rgba.size(); ++i) img.rgba[i] = i % 4 == 3 ? 255 : static_cast<std::uint8_t>(d(rng));
  return img;
}

// A smooth picture with structure, so that SSIM reacts to noise as on real images.
// Values stay in [48, 208]: an error of up to ±40 neither wraps nor clips.
Image smooth_image(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = img.at(x, y);
      p[0] = static_cast<std::uint8_t>(128 + 80 * std::sin(x * 0.11) * std::cos(y * 0.07));
      p[1] = static_cast<std::uint8_t>(128 + 80 * std::sin((x + y) * 0.05));
      p[2] = static_cast<std::uint8_t>(48 + (x * 3 + y * 2) % 160);
      p[3] = 255;
    }
  return img;
}

Image fill(int w, int h, std::array<int, 3> rgb) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 4; ++c) img.at(x, y)[c] = static_cast<std::uint8_t>(c == 3 ? 255 : rgb[static_cast<std::size_t>(c)]);
  return img;
}

// `img` with every R, G, B value moved by ±d (random sign; the caller keeps it in range) inside [x0, x0+w) × [y0, y0+h).
Image with_error(const Image& img, int d, int x0, int y0, int w, int h, unsigned seed = 1) {
  Image out = img;
  std::mt19937 rng(seed);
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x)
      for (int c = 0; c < 3; ++c) {
        std::uint8_t& v = out.at(x, y)[c];
        v = static_cast<std::uint8_t>(rng() % 2 ? v + d : v - d);
      }
  return out;
}

double analytic_psnr(double mse) { return 10 * std::log10(255.0 * 255.0 / mse); }

double constant_ssim(double m1, double m2) { return (2 * m1 * m2 + kC1) / (m1 * m1 + m2 * m2 + kC1); }

// Straight from the definition: a full 11×11 Gaussian window at every valid position.
double brute_force_ssim_luma(const Image& a, const Image& b) {
  std::array<double, 11> g{};
  double s = 0;
  for (int k = 0; k < 11; ++k) s += g[static_cast<std::size_t>(k)] = std::exp(-0.5 * (k - 5) * (k - 5) / 2.25);
  auto luma = [](const Image& i, int x, int y) {
    const std::uint8_t* p = i.at(x, y);
    return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
  };
  double total = 0;
  int n = 0;
  for (int y = 5; y < a.height - 5; ++y)
    for (int x = 5; x < a.width - 5; ++x) {
      double mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
      for (int j = -5; j <= 5; ++j)
        for (int i = -5; i <= 5; ++i) {
          const double w = g[static_cast<std::size_t>(j + 5)] * g[static_cast<std::size_t>(i + 5)] / (s * s);
          const double p = luma(a, x + i, y + j), q = luma(b, x + i, y + j);
          mx += w * p;
          my += w * q;
          xx += w * p * p;
          yy += w * q * q;
          xy += w * p * q;
        }
      const double vx = xx - mx * mx, vy = yy - my * my, vxy = xy - mx * my;
      total += ((2 * mx * my + kC1) * (2 * vxy + kC2)) / ((mx * mx + my * my + kC1) * (vx + vy + kC2));
      ++n;
    }
  return total / n;
}

}  // namespace

TEST(Metrics, IdenticalImagesGiveInfinitePsnrAndFpsnrAndSsimExactlyOne) {
  const Image a = random_image(64, 48, 3);
  MetricsOptions opt;
  opt.fovea = {0.2, 0.7};
  auto m = compute_metrics(a, a, opt);
  ASSERT_TRUE(m) << m.error().message;
  EXPECT_TRUE(std::isinf(m->psnr_db) && m->psnr_db > 0);
  EXPECT_TRUE(std::isinf(m->fpsnr_db) && m->fpsnr_db > 0);
  EXPECT_EQ(m->ssim, 1.0);
  opt.ssim_channels = SsimChannels::rgb;
  auto rgb = compute_metrics(a, a, opt);
  ASSERT_TRUE(rgb);
  EXPECT_EQ(rgb->ssim, 1.0);
}

TEST(Metrics, UniformErrorGivesTheAnalyticPsnrAndFpsnrEqualToIt) {
  // Every R, G, B value off by ±d: MSE = d² everywhere, so any weighting gives the same
  // FMSE and FPSNR == PSNR = 10 log10(255² / d²).
  const Image a = random_image(96, 64, 5, 20, 235);
  for (int d : {1, 3, 10}) {
    const Image b = with_error(a, d, 0, 0, a.width, a.height, static_cast<unsigned>(d));
    MetricsOptions opt;
    opt.fovea = {0.9, 0.1};
    auto m = compute_metrics(a, b, opt);
    ASSERT_TRUE(m) << m.error().message;
    EXPECT_NEAR(m->mse, double(d * d), 1e-9);
    EXPECT_NEAR(m->psnr_db, analytic_psnr(d * d), 1e-9);
    EXPECT_NEAR(m->fpsnr_db, m->psnr_db, 1e-9);
    EXPECT_NEAR(m->psnr_db, psnr(a, b), 1e-9);
  }
}

TEST(Metrics, SsimOfConstantImagesMatchesTheAnalyticValue) {
  // Constant images have no variance: SSIM = (2 m1 m2 + C1) / (m1² + m2² + C1).
  for (auto [m1, m2] : {std::pair{100, 110}, std::pair{20, 200}, std::pair{0, 255}, std::pair{128, 128}}) {
    const Image a = fill(32, 24, {m1, m1, m1}), b = fill(32, 24, {m2, m2, m2});
    auto s = ssim(a, b);
    ASSERT_TRUE(s) << s.error().message;
    EXPECT_NEAR(*s, constant_ssim(m1, m2), 1e-9) << m1 << " vs " << m2;
  }
  // Luma of a coloured constant image, and the RGB mean.
  const Image a = fill(20, 20, {200, 100, 50}), b = fill(20, 20, {210, 90, 50});
  const double ya = 0.299 * 200 + 0.587 * 100 + 0.114 * 50, yb = 0.299 * 210 + 0.587 * 90 + 0.114 * 50;
  EXPECT_NEAR(*ssim(a, b), constant_ssim(ya, yb), 1e-9);
  EXPECT_NEAR(*ssim(a, b, SsimChannels::rgb), (constant_ssim(200, 210) + constant_ssim(100, 90) + 1.0) / 3, 1e-9);
}

TEST(Metrics, SsimMatchesABruteForceWindowAndIsSymmetric) {
  const Image a = smooth_image(40, 31), b = with_error(smooth_image(40, 31), 12, 3, 5, 30, 20);
  const double ref = brute_force_ssim_luma(a, b);
  EXPECT_NEAR(*ssim(a, b), ref, 1e-12);
  EXPECT_NEAR(*ssim(b, a), ref, 1e-12);
  EXPECT_LT(ref, 0.99);
  // Exactly the window size: one position.
  const Image c = random_image(11, 11, 8), d = random_image(11, 11, 9);
  EXPECT_NEAR(*ssim(c, d), brute_force_ssim_luma(c, d), 1e-12);
}

TEST(Metrics, SsimDecreasesWithMoreNoise) {
  const Image a = smooth_image(120, 90);
  double last = 1.0;
  for (int d : {2, 5, 10, 20, 40}) {
    const Image b = with_error(a, d, 0, 0, a.width, a.height);
    const double s = *ssim(a, b);
    EXPECT_LT(s, last) << "noise " << d;
    last = s;
  }
  EXPECT_LT(last, 0.6);
}

TEST(Metrics, CutoffFrequencyAndEccentricity) {
  // f_c(0) = ln(64) / 0.106 = 39.23 cpd; halved at e = e2; capped at ppd / 2.
  EXPECT_NEAR(foveation_cutoff_cpd(0, 1000), std::log(64.0) / 0.106, 1e-12);
  EXPECT_NEAR(foveation_cutoff_cpd(kFoveaE2, 1000), 0.5 * std::log(64.0) / 0.106, 1e-12);
  EXPECT_DOUBLE_EQ(foveation_cutoff_cpd(0, 13.15), 6.575);
  EXPECT_DOUBLE_EQ(foveation_cutoff_cpd(5, 13.15), 6.575);
  EXPECT_LT(foveation_cutoff_cpd(30, 13.15), 6.575);
  EXPECT_NEAR(focal_length_px(13.15), 753.44, 0.01);
  const double f = 500;
  EXPECT_NEAR(eccentricity_deg(10, -7, 10, -7, f), 0, 1e-12);
  EXPECT_NEAR(eccentricity_deg(f, 0, 0, 0, f), 45, 1e-12);
  EXPECT_NEAR(eccentricity_deg(0, 0, 0, -f, f), 45, 1e-12);
  // The acos form of DESIGN.md section 3.
  const double px = 300, py = -120, gx = -80, gy = 200;
  const double c = (px * gx + py * gy + f * f) / (std::sqrt(px * px + py * py + f * f) * std::sqrt(gx * gx + gy * gy + f * f));
  EXPECT_NEAR(eccentricity_deg(px, py, gx, gy, f), std::acos(c) * 180 / std::numbers::pi, 1e-9);
  EXPECT_NEAR(eccentricity_deg(px, py, gx, gy, f), eccentricity_deg(gx, gy, px, py, f), 1e-12);
}

TEST(Metrics, AnErrorNearTheFoveaCostsMoreFpsnrThanInThePeriphery) {
  // 720×400 at 13.15 ppd: the corner is ~28° from the centre, where f_c is well below
  // the Nyquist cap that holds within ~11° of the fovea.
  const Image a = smooth_image(720, 400);
  MetricsOptions opt;
  opt.fovea = {0.5, 0.5};
  const Image near = with_error(a, 20, 350, 190, 20, 20), far = with_error(a, 20, 0, 0, 20, 20);
  auto mn = compute_metrics(a, near, opt), mf = compute_metrics(a, far, opt);
  ASSERT_TRUE(mn && mf);
  EXPECT_NEAR(mn->psnr_db, mf->psnr_db, 1e-9);  // same error, same plain PSNR
  EXPECT_LT(mn->fpsnr_db, mf->fpsnr_db - 3.0);
  EXPECT_LT(mn->fpsnr_db, mn->psnr_db);  // the error sits where the weights are largest
  EXPECT_GT(mf->fpsnr_db, mf->psnr_db);
  // Moving the fovea onto the peripheral error makes it count.
  opt.fovea = {10.0 / 720, 10.0 / 400};
  auto moved = compute_metrics(a, far, opt);
  ASSERT_TRUE(moved);
  EXPECT_LT(moved->fpsnr_db, mf->fpsnr_db - 3.0);
  // A lower ppd lowers the Nyquist cap and widens the flat region around the fovea.
  opt.fovea = {0.5, 0.5};
  opt.ppd = 40;
  auto sharp = compute_metrics(a, near, opt);
  ASSERT_TRUE(sharp);
  EXPECT_NE(sharp->fpsnr_db, mn->fpsnr_db);
}

TEST(Metrics, StereoUsesEachHalfsFovea) {
  const int w = 200, h = 120;
  const Image a = smooth_image(2 * w, h);
  // An error only in the right half, at 80 % across and 30 % down that half.
  const Image b = with_error(a, 15, w + 150, 28, 20, 20);
  MetricsOptions opt;
  opt.ppd = 60;  // the Nyquist cap (30 cpd) holds within ~0.7° (~40 px): weights vary across a small half
  opt.fovea = {0.8, 0.3};
  opt.fovea_right = {0.1, 0.9};
  auto away = compute_stereo_metrics(a, b, opt);
  opt.fovea = {0.1, 0.9};
  opt.fovea_right = {0.8, 0.3};
  auto onto = compute_stereo_metrics(a, b, opt);
  ASSERT_TRUE(away && onto) << (away ? onto.error().message : away.error().message);
  EXPECT_TRUE(std::isinf(away->left.fpsnr_db) && std::isinf(onto->left.fpsnr_db));
  EXPECT_EQ(away->left.ssim, 1.0);
  EXPECT_LT(onto->right.fpsnr_db, away->right.fpsnr_db - 3.0);
  EXPECT_LT(onto->combined.fpsnr_db, away->combined.fpsnr_db);
  // Each half is measured as an image of its own (own centre, own fovea).
  const Image rr = crop(a, Rect{w, 0, w, h}), rt = crop(b, Rect{w, 0, w, h});
  MetricsOptions single = opt;
  single.fovea = opt.fovea_right;
  auto alone = compute_metrics(rr, rt, single);
  ASSERT_TRUE(alone);
  EXPECT_DOUBLE_EQ(onto->right.fpsnr_db, alone->fpsnr_db);
  EXPECT_DOUBLE_EQ(onto->right.ssim, alone->ssim);
  // Combined: PSNR of the whole frame, FMSE pooled by weight, SSIM the mean of the halves.
  EXPECT_NEAR(onto->combined.psnr_db, psnr(a, b), 1e-9);
  EXPECT_NEAR(onto->combined.fmse,
              (onto->left.fmse * onto->left.weight_sum + onto->right.fmse * onto->right.weight_sum) /
                  (onto->left.weight_sum + onto->right.weight_sum),
              1e-12);
  EXPECT_DOUBLE_EQ(onto->combined.ssim, 0.5 * (onto->left.ssim + onto->right.ssim));
}

TEST(Metrics, ClearErrors) {
  const Image a = random_image(32, 32, 1), b = random_image(32, 31, 2), empty;
  MetricsOptions opt;
  auto expect_error = [](const auto& r, const std::string& needle) {
    ASSERT_FALSE(r) << needle;
    EXPECT_EQ(r.error().kind, foveal::ErrorKind::bad_input);
    EXPECT_NE(r.error().message.find(needle), std::string::npos) << r.error().message;
  };
  expect_error(compute_metrics(empty, a, opt), "reference image is empty");
  expect_error(compute_metrics(a, empty, opt), "test image is empty");
  expect_error(compute_metrics(a, b, opt), "32x32");
  expect_error(compute_stereo_metrics(a, b, opt), "sizes differ");
  for (double bad : {-0.01, 1.01, std::nan(""), std::numeric_limits<double>::infinity()}) {
    MetricsOptions o;
    o.fovea = {0.5, bad};
    expect_error(compute_metrics(a, a, o), "fovea");
    o.fovea = {0.5, 0.5};
    o.fovea_right = {bad, 0.5};
    expect_error(compute_stereo_metrics(a, a, o), "right fovea");
  }
  for (double bad : {0.0, -3.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    MetricsOptions o;
    o.ppd = bad;
    expect_error(compute_metrics(a, a, o), "ppd");
  }
  const Image odd = random_image(33, 20, 4);
  expect_error(compute_stereo_metrics(odd, odd, opt), "even width");
  const Image small = random_image(10, 40, 5);
  expect_error(compute_metrics(small, small, opt), "11x11");
  const Image narrow = random_image(20, 32, 6);  // 10-pixel-wide halves
  expect_error(compute_stereo_metrics(narrow, narrow, opt), "11x11");
  expect_error(ssim(a, a, Rect{25, 0, 10, 32}), "outside");
  // Fovea on the borders is allowed.
  opt.fovea = {0, 1};
  EXPECT_TRUE(compute_metrics(a, a, opt));
}

TEST(Metrics, SsimMatchesScikitImageOnADeterministicPair) {
  // Reference values from scikit-image 0.19.3 (Debian 12's python3-skimage):
  //   structural_similarity(A, B, gaussian_weights=True, sigma=1.5,
  //                         use_sample_covariance=False, data_range=255)
  // on float64 luma 0.299 R + 0.587 G + 0.114 B, and with channel_axis=2 on R, G, B.
  // docs/metrics.md has the script.
  const int w = 67, h = 45;
  Image a(w, h), b(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        const int v = (x * 7 + y * 13 + c * 50 + (x * y) % 17) % 256;
        a.at(x, y)[c] = static_cast<std::uint8_t>(v);
        b.at(x, y)[c] = static_cast<std::uint8_t>(std::clamp(v + (x * 31 + y * 17 + c * 5) % 21 - 10, 0, 255));
      }
  EXPECT_NEAR(*ssim(a, b), 0.989229051920368, 1e-12);
  EXPECT_NEAR(*ssim(a, b, SsimChannels::rgb), 0.979044627018439, 1e-12);
}

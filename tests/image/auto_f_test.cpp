// Automatic f: the CPU prediction of RMFR is what the compositor would produce from the
// same full frame, and the search finds the best f of a grid to within its resolution.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "foveal/image/auto_f.hpp"
#include "foveal/rmfr_mapping.hpp"

using namespace foveal::image;

namespace {
// Detail only along x in the left half of each eye: the best f_x and f_y differ.
Image anisotropic_frame(int w, int h) {
  Image img(2 * w, h);
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> v(0, 255);
  std::vector<int> column(static_cast<std::size_t>(w));
  for (auto& c : column) c = v(rng);
  for (int e = 0; e < 2; ++e)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        std::uint8_t* p = img.at(e * w + x, y);
        p[0] = p[1] = p[2] = static_cast<std::uint8_t>((column[static_cast<std::size_t>(x)] + y / 8 * 20) % 256);
        p[3] = 255;
      }
  return img;
}

double fpsnr_of(const Image& full, double sigma, double fx, double fy, const MetricsOptions& mo) {
  const int w = full.width / 2;
  const Image l = simulate_rmfr(crop(full, {0, 0, w, full.height}), sigma, fx, fy, mo.fovea.x, mo.fovea.y);
  const Image r = simulate_rmfr(crop(full, {w, 0, w, full.height}), sigma, fx, fy, mo.fovea_right.x, mo.fovea_right.y);
  auto m = compute_stereo_metrics(full, hconcat(l, r), mo);
  return m ? m->combined.fpsnr_db : NAN;
}
}  // namespace

TEST(AutoF, SimulationAtSigmaOneIsExact) {
  const Image full = anisotropic_frame(64, 48);
  const Image eye = crop(full, {0, 0, 64, 48});
  EXPECT_EQ(max_abs_diff(simulate_rmfr(eye, 1.0, 0.3, 0.3, 0.2, 0.7), eye), 0);
}

TEST(AutoF, FindsTheGridOptimumAndAgreesWithItsOwnPrediction) {
  const Image full = anisotropic_frame(120, 100);
  MetricsOptions mo;
  mo.ppd = 13.15 * 120 / 1440.0;
  mo.fovea = {0.4, 0.5};
  mo.fovea_right = {0.6, 0.5};
  auto est = estimate_rmfr_f(full, 2.0, mo);
  ASSERT_TRUE(est) << est.error().message;
  EXPECT_GE(est->fx, 0.05);
  EXPECT_LE(est->fx, 1.0);
  // The prediction is the metric of the simulated frame.
  EXPECT_NEAR(est->predicted_fpsnr_db, fpsnr_of(full, 2.0, est->fx, est->fy, mo), 0.05);
  double best = -INFINITY;
  for (double fx = 0.05; fx <= 1.0; fx += 0.05)
    for (double fy = 0.05; fy <= 1.0; fy += 0.05) best = std::max(best, fpsnr_of(full, 2.0, fx, fy, mo));
  EXPECT_GE(est->predicted_fpsnr_db, best - 0.2);
  EXPECT_LT(est->evaluations, 100);
}

TEST(AutoF, RejectsBadInput) {
  MetricsOptions mo;
  EXPECT_FALSE(estimate_rmfr_f(Image(3, 8), 2.0, mo));
  EXPECT_FALSE(estimate_rmfr_f(anisotropic_frame(16, 16), 0.5, mo));
}

// KFR's direction, pinned against the authors' Unity shaders (Pass1.shader, Pass2.shader
// of xmeng525/KernelFoveatedRendering_Unity), their formulas written out here again:
//   maxLr = log(0.5 · max over corners of |(corner - cursor) · resolution|), cursor in [-1, 1]
//   pass 1 (buffer -> screen): r = exp(maxLr · (σ·uv.x)^(1/kernel))
//   pass 2 (screen -> buffer): uv.x = (log r / maxLr)^kernel / σ
// With the kernel α = 4, buffer column 0.1 samples about 51 px from the fovea; the
// opposite direction (α applied in pass 1) would sample 1.0007 px there and crowd 90% of
// the buffer within 100 px.
#include <gtest/gtest.h>

#include <cmath>

#include "foveal/image/kfr_mapping.hpp"

using namespace foveal::image;

namespace {
constexpr int kW = 1440, kH = 1600;  // one Vive Pro Eye eye

// The Unity shaders' maxLr for a normalised eye position (their _eyeX, _eyeY).
double unity_max_lr(double eye_x, double eye_y) {
  const double cx = eye_x * 2 - 1, cy = eye_y * 2 - 1;
  double maxr = 0;
  for (double x : {1.0, -1.0})
    for (double y : {1.0, -1.0}) maxr = std::max(maxr, std::hypot((x - cx) * kW, (y - cy) * kH));
  return std::log(maxr * 0.5);
}
}  // namespace

TEST(KfrMapping, LogMaxIsTheUnityShadersMaxLr) {
  for (double x : {0.5, 0.0, 0.3, 1.0})
    for (double y : {0.5, 1.0, 0.8})
      EXPECT_NEAR(kfr_log_max(kW, kH, x * kW, y * kH), unity_max_lr(x, y), 1e-12) << x << "," << y;
  EXPECT_NEAR(kfr_log_max(kW, kH, 720, 800), 6.981275150306795, 1e-12);
  EXPECT_GT(kfr_log_max(1, 1, 0.5, 0.5), 0.0);  // at least ln 2
}

TEST(KfrMapping, BufferColumnsSampleTheRadiiOfTheAuthorsPassOne) {
  const double L = unity_max_lr(0.5, 0.5);
  for (double u : {0.0, 0.1, 0.25, 0.5, 0.9, 1.0})
    EXPECT_NEAR(kfr_radius(u, L, 4.0), std::exp(L * std::pow(u, 1.0 / 4.0)), 1e-9) << u;
  // Values of the reference formula, worked out by hand (a wrong direction gives 1.0007,
  // 1.028, 1.547 and 97.6 px).
  EXPECT_NEAR(kfr_radius(0.1, L, 4.0), 50.6966, 1e-3);
  EXPECT_NEAR(kfr_radius(0.25, L, 4.0), 139.2829, 1e-3);
  EXPECT_NEAR(kfr_radius(0.5, L, 4.0), 354.4365, 1e-3);
  EXPECT_NEAR(kfr_radius(0.9, L, 4.0), 897.6571, 1e-3);
  EXPECT_NEAR(kfr_radius(1.0, L, 4.0), std::hypot(720, 800), 1e-6);  // the farthest corner
  // α = 1 is plain log-polar either way.
  EXPECT_NEAR(kfr_radius(0.5, L, 1.0), std::exp(L / 2), 1e-9);
}

TEST(KfrMapping, ScreenRadiiReadTheColumnsOfTheAuthorsPassTwoAndInvertPassOne) {
  const double L = unity_max_lr(0.5, 0.5);
  EXPECT_NEAR(kfr_column(100.0, L, 4.0), std::pow(std::log(100.0) / L, 4.0), 1e-12);
  EXPECT_NEAR(kfr_column(100.0, L, 4.0), 0.18934, 1e-4);  // 19% of the buffer within 100 px
  EXPECT_EQ(kfr_column(0.2, L, 4.0), 0.0);                // below one pixel: the centre column
  for (double u = 0.0; u <= 1.0; u += 0.05) EXPECT_NEAR(kfr_column(kfr_radius(u, L, 4.0), L, 4.0), u, 1e-9) << u;
}

TEST(KfrMapping, MostTexelsSampleDistinctPixels) {
  // Computed from the reference formulas at σ = 2.6 with the fovea centred: 78.4% of the
  // texels hit distinct pixels (the opposite direction: 14.5%).
  EXPECT_NEAR(kfr_distinct_fraction(kW, kH, 2.6, 4.0, 0.5, 0.5), 0.7844, 0.005);
  EXPECT_NEAR(kfr_distinct_fraction(240, 270, 2.6, 4.0, 0.5, 0.5), 0.8742, 0.005);
  // Plain log-polar spends more of its texels on the same pixels near the fovea.
  EXPECT_LT(kfr_distinct_fraction(240, 270, 2.6, 1.0, 0.5, 0.5), 0.6);
}

TEST(KfrMapping, SimulationReproducesSmoothImages) {
  // A smooth image survives any consistent resampling; the GL test (tests/render) holds
  // the simulation to the compositor's KFR on a detailed one.
  Image eye(120, 100);
  for (int y = 0; y < eye.height; ++y)
    for (int x = 0; x < eye.width; ++x) {
      std::uint8_t* p = eye.at(x, y);
      p[0] = static_cast<std::uint8_t>(x + 60);
      p[1] = static_cast<std::uint8_t>(2 * y + 20);
      p[2] = 128, p[3] = 255;
    }
  for (double sigma : {1.0, 2.0, 3.0}) {
    const Image k = simulate_kfr(eye, sigma, 4.0, 0.25, 0.3);
    ASSERT_EQ(k.width, eye.width);
    EXPECT_GT(psnr(k, eye), 35.0) << sigma;
  }
  Image flat(40, 30);
  for (std::size_t i = 0; i < flat.rgba.size(); ++i) flat.rgba[i] = i % 4 == 3 ? 255 : 77;
  EXPECT_EQ(max_abs_diff(simulate_kfr(flat, 2.6, 4.0, 0.9, 0.1), flat), 0);
}

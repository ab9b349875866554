// RMFR in image space: sizes, identity at σ = 1, quality where it matters, borders.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "foveal/image/foveate.hpp"

using namespace foveal::image;

namespace {
Image noise_image(int w, int h) {
  Image img(w, h);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> v(0, 255);
  // Smooth-ish content: 4x4 blocks of random colour.
  std::vector<std::uint8_t> blocks(static_cast<std::size_t>((w / 4 + 1) * (h / 4 + 1) * 3));
  for (auto& b : blocks) b = static_cast<std::uint8_t>(v(rng));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y)[c] = blocks[static_cast<std::size_t>(((y / 4) * (w / 4 + 1) + x / 4) * 3 + c)];
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.at(x, y)[3] = 255;
  return img;
}
}  // namespace

TEST(Foveate, BufferSizeFollowsSigmaAndSigmaOneIsLossless) {
  const Image in = noise_image(200, 120);
  auto r = foveate(in, {2.0, 0.3, 0.3, 0.5, 0.5});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->reduced.width, 100);
  EXPECT_EQ(r->reduced.height, 60);
  EXPECT_EQ(r->output.width, 200);
  auto id = foveate(in, {1.0, 0.3, 0.3, 0.1, 0.9});
  ASSERT_TRUE(id);
  EXPECT_EQ(max_abs_diff(id->output, in), 0);
}

TEST(Foveate, FoveaIsSharperThanPeripheryAndBordersWork) {
  const Image in = noise_image(240, 160);
  for (double fx : {0.0, 0.5, 1.0})
    for (double fy : {0.0, 0.5, 1.0}) {
      auto r = foveate(in, {2.6, 0.3, 0.3, fx, fy});
      ASSERT_TRUE(r);
      const int cx = static_cast<int>(fx * 239), cy = static_cast<int>(fy * 159);
      const double near = psnr(in, r->output, Rect{cx - 8, cy - 8, 16, 16});
      const double whole = psnr(in, r->output);
      EXPECT_GT(near, whole + 3.0) << "fovea " << fx << "," << fy;
      EXPECT_GT(near, 20.0) << "fovea " << fx << "," << fy;
    }
}

TEST(Foveate, RejectsBadParameters) {
  const Image in = noise_image(16, 16);
  EXPECT_FALSE(foveate(in, {0.5, 0.3, 0.3, 0.5, 0.5}));
  EXPECT_FALSE(foveate(in, {NAN, 0.3, 0.3, 0.5, 0.5}));
  EXPECT_FALSE(foveate(in, {2.0, 0.0, 0.3, 0.5, 0.5}));
  EXPECT_FALSE(foveate(in, {2.0, 0.3, INFINITY, 0.5, 0.5}));
  EXPECT_FALSE(foveate(Image(), {2.0, 0.3, 0.3, 0.5, 0.5}));
  // NaN fovea falls back to the centre rather than producing NaN pixels.
  auto r = foveate(in, {2.0, 0.3, 0.3, NAN, 0.5});
  ASSERT_TRUE(r);
}

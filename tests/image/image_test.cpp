#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "foveal/image/image.hpp"
#include "test_support.hpp"

using namespace foveal::image;

TEST(Image, PsnrOfIdenticalImagesIsInfinite) {
  Image a(8, 8);
  EXPECT_TRUE(std::isinf(psnr(a, a)));
  EXPECT_EQ(max_abs_diff(a, a), 0);
}

TEST(Image, PsnrMatchesTheAnalyticValueForAKnownError) {
  // Every R, G, B value off by 5: MSE 25, PSNR = 10 log10(255²/25) = 34.15 dB.
  Image a(16, 16), b(16, 16);
  for (std::size_t i = 0; i < a.rgba.size(); ++i) {
    a.rgba[i] = 100;
    b.rgba[i] = i % 4 == 3 ? 0 : 105;  // alpha differs and is ignored
  }
  EXPECT_NEAR(psnr(a, b), 10 * std::log10(255.0 * 255.0 / 25.0), 1e-9);
  EXPECT_EQ(max_abs_diff(a, b), 5);
  // Only inside a rectangle: make the outside differ more.
  for (int y = 0; y < 16; ++y) b.at(15, y)[0] = 0;
  EXPECT_NEAR(psnr(a, b, Rect{0, 0, 8, 8}), 10 * std::log10(255.0 * 255.0 / 25.0), 1e-9);
  EXPECT_LT(psnr(a, b), 30.0);
}

TEST(Image, PngRoundTripAndClearErrors) {
  foveal::test::TempDir d;
  Image a(5, 3);
  for (std::size_t i = 0; i < a.rgba.size(); ++i) a.rgba[i] = static_cast<std::uint8_t>(i * 7);
  ASSERT_TRUE(save_png(d.path("a.png"), a));
  auto b = load(d.path("a.png"));
  ASSERT_TRUE(b) << b.error().message;
  EXPECT_EQ(b->rgba, a.rgba);
  auto missing = load(d.path("nope.png"));
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("nope.png"), std::string::npos);
  foveal::test::write_file(d.path("bad.png"), "not a png");
  auto bad = load(d.path("bad.png"));
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("bad.png"), std::string::npos);
}

TEST(Image, CropAndConcat) {
  Image a(4, 2), b(3, 2);
  a.at(3, 1)[0] = 9;
  b.at(0, 0)[1] = 7;
  Image c = hconcat(a, b);
  EXPECT_EQ(c.width, 7);
  EXPECT_EQ(c.at(3, 1)[0], 9);
  EXPECT_EQ(c.at(4, 0)[1], 7);
  Image d = crop(c, Rect{3, 1, 10, 10});
  EXPECT_EQ(d.width, 4);
  EXPECT_EQ(d.height, 1);
  EXPECT_EQ(d.at(0, 0)[0], 9);
}

// The native FovVideoVDP's sanity: identical is 10 JOD, more distortion is lower, and the
// same distortion away from the fixation is less visible (docs/metrics.md, "JOD").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "foveal/perception/jod.hpp"

namespace foveal::perception {
namespace {

constexpr int kW = 256, kH = 160;

EyeGeometry vive_like() { return eye_geometry(DisplayModel::vive_pro_eye(), Eye::left, 1440, 1600); }
// A window of the Vive's left eye at its own pixel density (753.6 px focal length).
EyeGeometry window(int w, int h) { return {w, h, 753.6, w / 2.0, h / 2.0}; }

std::uint8_t clamp8(double v) { return static_cast<std::uint8_t>(std::lround(std::fmin(255.0, std::fmax(0.0, v)))); }

image::Image texture(int w, int h) {
  image::Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double v = 128 + 60 * std::sin(x * 0.35) * std::cos(y * 0.21) + 30 * std::sin((x + 2 * y) * 0.9);
      std::uint8_t* p = img.at(x, y);
      p[0] = clamp8(v);
      p[1] = clamp8(v * 0.9 + 10);
      p[2] = clamp8(255 - v);
      p[3] = 255;
    }
  return img;
}

// Adds ±amp (a fixed pseudo-random pattern) inside [x0, x1).
image::Image noisy(const image::Image& src, double amp, int x0 = 0, int x1 = 1 << 30) {
  image::Image out = src;
  std::uint32_t s = 12345;
  for (int y = 0; y < src.height; ++y)
    for (int x = 0; x < src.width; ++x) {
      s = s * 1664525u + 1013904223u;
      const double n = (static_cast<double>(s >> 8) / 16777216.0 - 0.5) * 2 * amp;
      if (x < x0 || x >= x1) continue;
      for (int c = 0; c < 3; ++c) out.at(x, y)[c] = clamp8(src.at(x, y)[c] + n);
    }
  return out;
}

TEST(Jod, IdenticalIsTenAndGeometryFollowsTheDisplayModel) {
  const EyeGeometry g = vive_like();
  EXPECT_NEAR(g.focal_px, 753.6, 0.1);
  EXPECT_NEAR(g.ppd(), 13.153, 0.01);  // FovVideoVDP's htc_vive_pro: 13.15 px/deg
  JodMetric m(window(kW, kH), Photometry{});
  const image::Image ref = texture(kW, kH);
  auto s = m.still(ref, ref, std::nullopt);
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_DOUBLE_EQ(s->jod, 10.0);
  EXPECT_EQ(s->bands, 5);
}

TEST(Jod, MoreNoiseIsLowerJodMonotonically) {
  JodMetric m(window(kW, kH), Photometry{});
  const image::Image ref = texture(kW, kH);
  double last = 10.0;
  for (double amp : {2.0, 6.0, 12.0, 24.0, 48.0}) {
    auto s = m.still(ref, noisy(ref, amp), Fixation{kW / 2.0, kH / 2.0});
    ASSERT_TRUE(s) << s.error().message;
    EXPECT_LT(s->jod, last) << "noise ±" << amp;
    last = s->jod;
  }
  EXPECT_LT(last, 8.0);
  EXPECT_GT(last, 0.0);
}

TEST(Jod, NoiseAwayFromTheFixationIsLessVisible) {
  const int w = 640, h = 160;
  JodMetric m(window(w, h), Photometry{});
  const image::Image ref = texture(w, h);
  const image::Image test = noisy(ref, 16, 0, 80);  // a strip at the left edge
  auto near = m.still(ref, test, Fixation{40, h / 2.0});
  auto far = m.still(ref, test, Fixation{600, h / 2.0});
  auto none = m.still(ref, test, std::nullopt);
  ASSERT_TRUE(near && far && none);
  EXPECT_GT(far->jod, near->jod + 0.05);  // 37° away
  EXPECT_LE(none->jod, near->jod + 1e-9);  // not foveated: foveal sensitivity everywhere
}

TEST(Jod, BrighterDisplayShowsMore) {
  const image::Image ref = texture(kW, kH);
  const image::Image test = noisy(ref, 8);
  auto dim = JodMetric(window(kW, kH), Photometry{10, 0.01}).still(ref, test, std::nullopt);
  auto bright = JodMetric(window(kW, kH), Photometry{300, 0.3}).still(ref, test, std::nullopt);
  ASSERT_TRUE(dim && bright);
  EXPECT_LT(bright->jod, dim->jod);
}

TEST(Jod, WrongSizeIsRefusedWithTheSizes) {
  JodMetric m(window(kW, kH), Photometry{});
  auto s = m.still(texture(kW, kH), texture(kW + 2, kH), std::nullopt);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().kind, ErrorKind::bad_input);
  EXPECT_NE(s.error().message.find("258x160"), std::string::npos) << s.error().message;
}

TEST(Jod, VideoOfIdenticalFramesIsTenAndFlickerIsSeen) {
  JodMetric m(window(kW, kH), Photometry{});
  const image::Image ref = texture(kW, kH);
  auto same = m.video(90);
  auto flicker = m.video(90);
  auto slow = m.video(2);  // one frame per 250 ms: the sustained channel alone
  ASSERT_TRUE(same && flicker && slow);
  for (int k = 0; k < 10; ++k) {
    ASSERT_TRUE(same->push(ref, ref, Fixation{kW / 2.0, kH / 2.0}));
    const image::Image t = noisy(ref, k % 2 ? 6.0 : 0.0);
    ASSERT_TRUE(flicker->push(ref, t, Fixation{kW / 2.0, kH / 2.0}));
    ASSERT_TRUE(slow->push(ref, t, std::nullopt));
  }
  EXPECT_DOUBLE_EQ(same->score()->jod, 10.0);
  EXPECT_LT(flicker->score()->jod, 10.0);
  EXPECT_LT(slow->score()->jod, 10.0);
  EXPECT_EQ(flicker->score()->frames, 10);
  EXPECT_FALSE(m.video(0));
  EXPECT_FALSE(m.video(5000));
  auto empty = m.video(30);
  EXPECT_FALSE(empty->score());
}

TEST(Jod, DegenerateInputsAreRefusedOrScoredWithoutBands) {
  JodMetric m(window(kW, kH), Photometry{});
  const image::Image ref = texture(kW, kH);
  auto nan = m.still(ref, ref, Fixation{std::nan(""), 3});
  ASSERT_FALSE(nan);
  EXPECT_NE(nan.error().message.find("finite"), std::string::npos) << nan.error().message;
  auto v = m.video(30);
  EXPECT_FALSE(v->push(ref, ref, Fixation{1, INFINITY}));
  JodMetric dark(window(kW, kH), Photometry{100, std::nan("")});
  EXPECT_FALSE(dark.still(ref, ref, std::nullopt));
  EXPECT_FALSE(dark.video(30));
  JodMetric tiny(window(1, 1), Photometry{});
  auto t = tiny.still(texture(1, 1), noisy(texture(1, 1), 30), std::nullopt);
  ASSERT_TRUE(t);
  EXPECT_EQ(t->bands, 0);
  EXPECT_DOUBLE_EQ(t->jod, 10.0);
}

TEST(Jod, ThreadsGiveTheSameScore) {
  const image::Image ref = texture(kW, kH);
  const image::Image test = noisy(ref, 10);
  const Fixation fix{100, 60};
  auto one = JodMetric(window(kW, kH), Photometry{}, Parameters{}, 1).still(ref, test, fix);
  auto three = JodMetric(window(kW, kH), Photometry{}, Parameters{}, 3).still(ref, test, fix);
  ASSERT_TRUE(one && three);
  EXPECT_NEAR(one->jod, three->jod, 1e-9);
  auto v1 = JodMetric(window(kW, kH), Photometry{}, Parameters{}, 1).video(60);
  auto v3 = JodMetric(window(kW, kH), Photometry{}, Parameters{}, 3).video(60);
  for (int k = 0; k < 4; ++k) {
    ASSERT_TRUE(v1->push(ref, k % 2 ? test : ref, fix));
    ASSERT_TRUE(v3->push(ref, k % 2 ? test : ref, fix));
  }
  EXPECT_NEAR(v1->score()->jod, v3->score()->jod, 1e-9);
}

}  // namespace
}  // namespace foveal::perception

// The quad views' geometry (openxr/src/inset.*): the inner view always inside the outer
// one, its motion between the gaze and the fixed place without a jump, and the views'
// sizes from the user's EFR pair.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "inset.hpp"

namespace foveal::openxr {
namespace {

// Monado's simulated HMD's left eye, roughly: ±45° across, a little asymmetric.
const TanRect kOuter{-1.0f, 0.9f, -1.0f, 1.0f};

void expect_inside(const TanRect& inner, const TanRect& outer) {
  EXPECT_GT(inner.left, outer.left);
  EXPECT_LT(inner.right, outer.right);
  EXPECT_GT(inner.down, outer.down);
  EXPECT_LT(inner.up, outer.up);
  EXPECT_LT(inner.left, inner.right);
  EXPECT_LT(inner.down, inner.up);
}

TEST(QuadInset, TheInnerViewIsCentredOnTheGazeAndSlidesInwardAtTheEdges) {
  const TanRect centred = place_inset(kOuter, 0.35f, 0.35f, 0.1f, -0.2f);
  EXPECT_NEAR(0.5f * (centred.left + centred.right), 0.1f, 1e-6f);
  EXPECT_NEAR(0.5f * (centred.down + centred.up), -0.2f, 1e-6f);
  EXPECT_NEAR(centred.right - centred.left, 0.35f * 1.9f, 1e-6f);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  for (float x : {-5.0f, -1.0f, 0.9f, 3.0f, nan, inf, -inf})
    for (float y : {-5.0f, 0.0f, 1.0f, nan}) {
      const TanRect r = place_inset(kOuter, 0.35f, 0.35f, x, y);
      expect_inside(r, kOuter);
      EXPECT_NEAR(r.right - r.left, 0.35f * 1.9f, 1e-5f) << "the size is kept at the edges";
    }
  expect_inside(place_inset(kOuter, 1.0f, 1.0f, 0, 0), kOuter);  // a share of 1 still lies inside
}

TEST(QuadInset, LosingAndRegainingTheGazeMovesTheInsetWithoutAJump) {
  InsetSettings s;
  InsetMotion m;
  const std::int64_t frame = 11'111'111;  // 90 Hz
  std::int64_t t = 1'000'000'000;
  TanRect prev = m.update(kOuter, s, true, 0.4f, 0.5f, t);
  EXPECT_NEAR(0.5f * (prev.left + prev.right), 0.4f, 1e-6f) << "the first frame starts on the gaze";
  const TanRect fixed = place_inset(kOuter, s.fixed_share_x, s.fixed_share_y, -0.05f, 0.0f);
  float largest_step = 0;
  for (int i = 1; i <= 60; ++i) {  // lost for 60 frames, then back
    const bool gaze = i > 30;
    const TanRect r = m.update(kOuter, s, gaze, 0.4f, 0.5f, t + i * frame);
    expect_inside(r, kOuter);
    largest_step = std::max({largest_step, std::abs(r.left - prev.left), std::abs(r.up - prev.up)});
    if (i == 30) {
      EXPECT_NEAR(r.left, fixed.left, 1e-6f) << "after the transition: the fixed inset";
      EXPECT_NEAR(r.up, fixed.up, 1e-6f);
    }
    prev = r;
  }
  EXPECT_NEAR(0.5f * (prev.left + prev.right), 0.4f, 1e-6f) << "back on the gaze";
  // The whole move is about 0.7 in tangent: spread over 150 ms it is no jump.
  EXPECT_LT(largest_step, 0.2f);
  EXPECT_GT(largest_step, 0.0f);
}

TEST(QuadInset, TheSameDisplayTimeGivesTheSameInsetAndTimeNeverOverflows) {
  InsetSettings s;
  InsetMotion m;
  m.update(kOuter, s, true, 0.3f, 0.0f, 5'000'000'000);
  const TanRect a = m.update(kOuter, s, false, 0, 0, 5'050'000'000);
  const TanRect b = m.update(kOuter, s, false, 0, 0, 5'050'000'000);
  EXPECT_EQ(a.left, b.left);
  EXPECT_EQ(a.up, b.up);
  const TanRect far = m.update(kOuter, s, false, 0, 0, std::numeric_limits<std::int64_t>::max());
  expect_inside(far, kOuter);
  EXPECT_EQ(m.follow(), 0.0f);
}

TEST(QuadInset, SizesFollowTheEyesLevels) {
  const std::uint32_t w[2] = {1440, 1440}, h[2] = {1600, 1600};
  const float density[2] = {1.0f / 3.0f, 1.0f / 2.0f};  // left non-dominant σ 3, right dominant σ 2
  const QuadSizes q = quad_sizes(w, h, density, 0.35f, 0.35f);
  EXPECT_EQ(q.width[0], 480u);
  EXPECT_EQ(q.height[0], 533u);
  EXPECT_EQ(q.width[1], 720u);
  EXPECT_EQ(q.height[1], 800u);
  EXPECT_EQ(q.width[2], 504u);
  EXPECT_EQ(q.width[3], 504u);
  EXPECT_EQ(q.height[3], 560u);
}

}  // namespace
}  // namespace foveal::openxr

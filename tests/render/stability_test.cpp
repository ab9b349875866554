// The stability matrix (docs/stability.md): every method, the fovea on every corner,
// border and one pixel inside it, extreme levels and f, odd and non-square viewports,
// NaN/Inf/off-viewport fovea input, on patterns, a glTF scene and scenes with blended
// and transmissive surfaces. Every output pixel is written (the output is first
// filled with a sentinel), none is NaN or Inf, and the fovea patch stays within a stated
// bound of the centred case.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "gl_support.hpp"
#include "khronos_models.hpp"
#include "test_support.hpp"

using namespace foveal;
using render::Method;

namespace {

constexpr float kSentinel = -7.0f;

// Renders with the output pre-filled with the sentinel; returns how many float values
// are non-finite or still the sentinel.
std::size_t bad_values(render::Compositor& c, const render::Scene& s, const render::FrameParams& p) {
  const float fill[4] = {kSentinel, kSentinel, kSentinel, kSentinel};
  glClearNamedFramebufferfv(c.output_framebuffer(), GL_COLOR, 0, fill);
  auto t = c.render(s, p);
  EXPECT_TRUE(t) << (t ? "" : t.error().message);
  std::size_t bad = 0;
  for (float v : c.read_float()) bad += (!std::isfinite(v) || v == kSentinel) ? 1 : 0;
  return bad;
}

std::vector<std::pair<double, double>> foveae(int w, int h) {
  const double in_x = 1.0 / w, in_y = 1.0 / h;  // one pixel inside the border
  return {{0, 0},     {1, 0},         {0, 1},         {1, 1},         {0.5, 0},     {0.5, 1},
          {0, 0.5},   {1, 0.5},       {in_x, in_y},   {1 - in_x, 0.5}, {0.5, 1 - in_y}, {0.5, 0.5},
          {0.37, 0.81}};
}

// The matrix runs through both pipelines (docs/stability.md): the fixture's parameter.
render::Pipeline g_pipeline = render::Pipeline::gbuffer;

render::FrameParams params(Method m, double sigma, double fx, double fy, double x, double y) {
  render::FrameParams p;
  p.method = m;
  p.pipeline = g_pipeline;
  for (auto& e : p.eyes) e = {sigma, fx, fy, x, y, 4.0, 0.0};
  return p;
}

class Stability : public ::testing::TestWithParam<render::Pipeline> {
 protected:
  void SetUp() override { g_pipeline = GetParam(); }
};

}  // namespace

INSTANTIATE_TEST_SUITE_P(Pipelines, Stability, ::testing::ValuesIn(render::all_pipelines()),
                         [](const ::testing::TestParamInfo<render::Pipeline>& p) { return std::string(render::pipeline_name(p.param)); });

TEST_P(Stability, EveryMethodLevelAndFoveaOnOddViewports) {
  ASSERT_TRUE(test::gl_ready());
  render::Scene s = test::scene("pattern:checker");
  for (auto [w, h] : {std::pair{97, 61}, std::pair{64, 121}}) {
    render::Compositor c = test::make_compositor(2 * w, h, true);
    for (Method m : render::all_methods())
      for (double sigma : {1.0, 1.01, 1.4, 2.0, 2.6, 3.0, 4.0, 8.0})
        for (auto [x, y] : foveae(w, h))
          EXPECT_EQ(bad_values(c, s, params(m, sigma, 0.3, 0.3, x, y)), 0u)
              << render::method_name(m) << " sigma " << sigma << " fovea " << x << "," << y << " eye " << w << "x" << h;
  }
}

// The visibility pipeline's triangle path (the patterns have none): a glTF scene through
// the same foveae, every method, the extreme levels.
TEST_P(Stability, EveryMethodAndFoveaOnAScene) {
  ASSERT_TRUE(test::gl_ready());
  render::Scene s = test::scene(test::source_path("data/scenes/WaterBottle/WaterBottle.gltf"));
  const int w = 97, h = 61;
  render::Compositor c = test::make_compositor(2 * w, h, true);
  for (Method m : render::all_methods())
    for (double sigma : {1.0, 2.6, 8.0})
      for (auto [x, y] : foveae(w, h))
        EXPECT_EQ(bad_values(c, s, params(m, sigma, 0.3, 0.3, x, y)), 0u)
            << render::method_name(m) << " sigma " << sigma << " fovea " << x << "," << y;
}

// Surfaces drawn after the inverse pass: alphaMode BLEND (AlphaBlendModeTest) and
// KHR_materials_transmission (TransmissionTest, which also reads the mipmapped copy of
// the opaque result), through the same foveae, every method, the extreme levels and
// NaN/Inf/off-viewport fovea input; in the visibility pipeline also shaded at the kept
// samples (--blend-at samples: the peel, the composite and the resolve transmission reads).
TEST_P(Stability, EveryMethodAndFoveaOnBlendedAndTransmissiveSurfaces) {
  ASSERT_TRUE(test::gl_ready());
  const int w = 97, h = 61;
  render::Compositor c = test::make_compositor(2 * w, h, true);
  const double inf = INFINITY;
  std::vector<std::pair<double, double>> inputs = foveae(w, h);
  for (auto xy : std::vector<std::pair<double, double>>{{NAN, 0.5}, {inf, -inf}, {-3, 0.5}}) inputs.push_back(xy);
  std::vector<render::BlendAt> where = {render::BlendAt::output};
  if (g_pipeline == render::Pipeline::visibility) where.push_back(render::BlendAt::samples);
  for (const char* model : {"AlphaBlendModeTest", "TransmissionTest"}) {
    render::Scene s = test::scene(test::khronos(model));
    for (Method m : render::all_methods())
      for (double sigma : {1.0, 8.0})  // the extremes (the scene test above has 2.6)
        for (auto [x, y] : inputs)
          for (render::BlendAt at : where) {
            render::FrameParams p = params(m, sigma, 0.3, 0.3, x, y);
            p.blend_at = at;
            EXPECT_EQ(bad_values(c, s, p), 0u) << model << " " << render::method_name(m) << " sigma " << sigma << " fovea " << x
                                               << "," << y << " blend at " << render::blend_at_name(at);
          }
  }
}

TEST_P(Stability, RmfrAtExtremeF) {
  ASSERT_TRUE(test::gl_ready());
  render::Scene s = test::scene("pattern:noise");
  render::Compositor c = test::make_compositor(2 * 97, 61, true);
  for (double f : {0.01, 0.05, 0.3, 1.0, 10.0})
    for (double sigma : {1.01, 2.6, 8.0})
      for (auto [x, y] : foveae(97, 61))
        EXPECT_EQ(bad_values(c, s, params(Method::rmfr, sigma, f, 10.0 / f * 0.01, x, y)), 0u)
            << "f " << f << " sigma " << sigma << " fovea " << x << "," << y;
}

TEST_P(Stability, NanInfAndOffViewportFoveaInput) {
  ASSERT_TRUE(test::gl_ready());
  render::Scene s = test::scene("pattern:checker");
  render::Compositor c = test::make_compositor(2 * 97, 61, true);
  const double inf = INFINITY;
  for (Method m : render::all_methods())
    for (auto [x, y] : std::vector<std::pair<double, double>>{{NAN, 0.5}, {0.5, NAN}, {inf, -inf}, {-3, 0.5}, {0.5, 9}, {1e300, -1e300}})
      EXPECT_EQ(bad_values(c, s, params(m, 2.6, 0.3, 0.3, x, y)), 0u) << render::method_name(m) << " fovea " << x << "," << y;
}

TEST_P(Stability, FoveaPatchWithinItsBoundOfTheCentredCase) {
  // Bounds (docs/stability.md): 1 dB on corners, borders, one pixel inside them and the
  // centre for every method but KFR (7 dB: its log-polar buffer spends texels outside the
  // viewport, three quarters of its angles with the fovea on a corner, where L grows too;
  // measured 6.7 dB at 240×270). In between, RMFR's side of the fovea towards the nearer border is sampled at
  // (f + D_near)/(f·σ), so a fovea at 81% of the height loses up to 5 dB: measured here.
  // The visibility pipeline filters each texel over its footprint, which that density
  // sets: RMFR 2 dB on the borders (measured 1.9 one pixel inside the top border) and
  // 6 dB in between (5.6). A centred patch above 50 dB (exact in 8 bits) counts as 50.
  ASSERT_TRUE(test::gl_ready());
  render::Scene s = test::scene("pattern:checker");
  const int w = 240, h = 270;
  render::Compositor c = test::make_compositor(2 * w, h);
  const image::Image full = test::render_frame(c, s, params(Method::full, 1, 0.3, 0.3, 0.5, 0.5));
  for (Method m : {Method::rmfr, Method::kfr, Method::hyperbolic, Method::linear}) {
    const bool vis = g_pipeline == render::Pipeline::visibility;
    const double bound = m == Method::kfr ? 7.0 : (vis && m == Method::rmfr) ? 2.0 : 1.0;
    auto patch = [&](double x, double y) {
      const image::Image img = test::render_frame(c, s, params(m, 2.6, 0.3, 0.3, x, y));
      return image::psnr(full, img, test::fovea_patch(c, Eye::left, x, y, 32));
    };
    const double centred = std::min(patch(0.5, 0.5), 50.0);
    for (auto [x, y] : foveae(w, h)) {
      const bool between = x == 0.37;
      const double b = between && m == Method::rmfr ? (vis ? 6.0 : 5.0) : bound;
      EXPECT_GE(patch(x, y), centred - b) << render::method_name(m) << " fovea " << x << "," << y << " centred " << centred;
    }
  }
}

// Issue 31's corner: σ 8, f 0.01, the fovea on a corner. The far edge was sampled at
// 1/808 texels per pixel: two texel columns covered 63% of each eye's width, and at full
// size (1440×800) 17% of Dungeon's pixels differed from full by more than 128. The plan's
// periphery floor raises f to 1/7 there (tests/foveation/periphery_floor_test.cpp); the
// GPU takes that f, and the picture stays: 0.43% (G-buffer) and 0.28% (visibility) of
// pixels here, against 12.4% and 10.5% with the plan built without the floor.
TEST_P(Stability, RmfrPeripheryFloorKeepsTheCornersPicture) {
  ASSERT_TRUE(test::gl_ready());
  render::Scene s = test::scene(test::source_path("data/scenes/Dungeon/dungeon_simplified.gltf"));
  render::Compositor c = test::make_compositor(2 * 240, 270);
  const image::Image full = test::render_frame(c, s, params(Method::full, 1, 0.3, 0.3, 0.5, 0.5));
  const image::Image corner = test::render_frame(c, s, params(Method::rmfr, 8, 0.01, 0.01, 1, 1));
  EXPECT_EQ(image::max_abs_diff(corner, test::render_frame(c, s, params(Method::rmfr, 8, 1.0 / 7, 1.0 / 7, 1, 1))), 0);
  std::size_t far_off = 0;
  for (int y = 0; y < full.height; ++y)
    for (int x = 0; x < full.width; ++x)
      for (int k = 0; k < 3; ++k)
        if (std::abs(full.at(x, y)[k] - corner.at(x, y)[k]) > 128) {
          ++far_off;
          break;
        }
  EXPECT_LT(static_cast<double>(far_off) / (static_cast<double>(full.width) * full.height), 0.02);
}

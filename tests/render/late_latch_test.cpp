// Late latch (docs/latency.md): the fovea a frame uses is the one the latch gives after
// the left eye's full-resolution pass, not the one the frame began with, in both
// pipelines.
#include <gtest/gtest.h>

#include "foveal/image/metrics.hpp"
#include "gl_support.hpp"
#include "test_support.hpp"

using namespace foveal;
using render::Method;
using render::Pipeline;

namespace {

constexpr int kW = 480, kH = 270;

render::FrameParams in(Pipeline p, render::FrameParams f) {
  f.pipeline = p;
  return f;
}

TEST(LateLatch, AFoveaSetBetweenThePassesIsTheOneTheFrameShows) {
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = test::make_compositor(kW, kH);
  render::Scene s = test::scene(test::source_path("data/scenes/WaterBottle/WaterBottle.gltf"));
  for (Pipeline p : render::all_pipelines()) {
    const render::FrameParams before = in(p, test::frame(Method::rmfr, 2.5, 0.2, 0.3));
    const render::FrameParams after = in(p, test::frame(Method::rmfr, 2.5, 0.8, 0.7));
    const image::Image direct = test::render_frame(c, s, after);
    int calls = 0;
    const render::FoveaLatch latch = [&](std::array<render::EyeFoveation, 2>& eyes) {
      ++calls;
      for (auto& e : eyes) e.fovea_x = 0.8, e.fovea_y = 0.7;
    };
    auto t = c.render(s, before, latch);
    ASSERT_TRUE(t) << t.error().message;
    EXPECT_EQ(calls, 1) << render::pipeline_name(p);
    for (Eye e : kEyes) {
      EXPECT_NEAR(c.plan(e).fovea.x, 0.8, 1e-6) << render::pipeline_name(p) << " " << eye_name(e);
      EXPECT_NEAR(c.plan(e).fovea.y, 0.7, 1e-6) << render::pipeline_name(p) << " " << eye_name(e);
    }
    // The frame is the latched fovea's, pixel for pixel, not the one it began with.
    const image::Image latched = c.read_image();
    EXPECT_TRUE(latched.rgba == direct.rgba) << render::pipeline_name(p) << ": PSNR " << image::psnr(direct, latched);
    EXPECT_LT(image::psnr(test::render_frame(c, s, before), latched), 60.0) << render::pipeline_name(p);
    EXPECT_LE(t->start_ns, t->latch_ns);
    EXPECT_LE(t->latch_ns, t->gpu_done_ns);
  }
}

TEST(LateLatch, NonFiniteLatchedPointsKeepTheFramesOwn) {
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = test::make_compositor(kW, kH);
  render::Scene s = test::scene("pattern:checker");
  const render::FrameParams p = in(Pipeline::visibility, test::frame(Method::rmfr, 2.0, 0.25, 0.5));
  auto t = c.render(s, p, [](std::array<render::EyeFoveation, 2>& eyes) {
    eyes[0].fovea_x = std::nan("");
    eyes[1].fovea_x = 7.0;  // clamped to the edge
  });
  ASSERT_TRUE(t) << t.error().message;
  EXPECT_NEAR(c.plan(Eye::left).fovea.x, 0.25, 1e-6);
  EXPECT_NEAR(c.plan(Eye::right).fovea.x, 1.0, 1e-6);
}

}  // namespace

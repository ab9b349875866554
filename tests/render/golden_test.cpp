// Golden images of pattern scenes, full and every foveation method with EFR (tolerance: PSNR >= 40 dB against
// the committed image; a diff image is written on failure).
#include <gtest/gtest.h>

#include "gl_support.hpp"

using namespace foveal;
using render::Method;

namespace {
// Every method: full, then each foveation method with EFR (σ 2 right, 3 left) and a
// different fovea per eye; NAME_METHOD.png.
void golden(const std::string& spec, const std::string& name) {
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = test::make_compositor(480, 270);
  render::Scene s = test::scene(spec);
  test::expect_matches_golden(test::render_frame(c, s, test::frame(Method::full, 1.0)), name + "_full");
  for (Method m : render::all_methods()) {
    if (m == Method::full) continue;
    render::FrameParams p = render::efr_frame(m, Eye::right, 2.0, 3.0, 0.3, 0.3);
    p.eyes[0].fovea_x = 0.3, p.eyes[0].fovea_y = 0.4;
    p.eyes[1].fovea_x = 0.8, p.eyes[1].fovea_y = 0.9;
    test::expect_matches_golden(test::render_frame(c, s, p), name + "_" + render::method_name(m));
  }
}
}  // namespace

TEST(Golden, Checker) { golden("pattern:checker", "checker"); }
TEST(Golden, VerticalStripes) { golden("pattern:stripes-v", "stripes_v"); }
TEST(Golden, RotatedNoise) { golden("pattern:noise@30", "noise_30"); }

// Lens distortion folded into the resolve pass: it matches a separate distortion pass
// applied to the undistorted frame, it leaves the corners black, and a golden image.
#include <gtest/gtest.h>

#include <cmath>

#include "gl_support.hpp"
#include "test_support.hpp"

using namespace foveal;

namespace {
render::Compositor lens_compositor(int w, int h, bool distortion) {
  auto model = DisplayModel::load(test::source_path("data/display/htc_vive_pro_eye_lens.json"));
  if (!model) std::abort();
  render::CompositorOptions o;
  o.width = w;
  o.height = h;
  o.model = *model;
  o.distortion = distortion;
  o.shadow_map_size = 512;
  auto c = render::Compositor::create(o, test::source_shaders());
  if (!c) std::abort();
  return std::move(*c);
}

double srgb_to_linear(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }
double linear_to_srgb(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055; }

// The separate pass, on the CPU: each channel of each panel pixel samples the
// undistorted frame bilinearly (in linear light, as the GPU filters sRGB textures).
image::Image distort(const image::Image& in, const DisplayModel& m) {
  image::Image out(in.width, in.height);
  const int w = in.width / 2, h = in.height;
  const float wf = static_cast<float>(w), hf = static_cast<float>(h);
  for (Eye e : kEyes) {
    const LensDistortion& d = m.distortion[static_cast<std::size_t>(e)];
    const int x0 = e == Eye::left ? 0 : w;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        std::uint8_t* o = out.at(x0 + x, y);
        o[3] = 255;
        for (int c = 0; c < 3; ++c) {
          const glm::vec2 s = d.source({(static_cast<float>(x) + 0.5f) / wf, (static_cast<float>(y) + 0.5f) / hf}, c, m.eye(e));
          if (s.x < 0 || s.x > 1 || s.y < 0 || s.y > 1) {
            o[c] = 0;
            continue;
          }
          const double fx = std::clamp(double(s.x) * w - 0.5, 0.0, w - 1.0), fy = std::clamp(double(s.y) * h - 0.5, 0.0, h - 1.0);
          const int ix = std::min(int(fx), w - 2), iy = std::min(int(fy), h - 2);
          const double tx = fx - ix, ty = fy - iy;
          auto at = [&](int xx, int yy) { return srgb_to_linear(in.at(x0 + xx, yy)[c] / 255.0); };
          const double v = (at(ix, iy) * (1 - tx) + at(ix + 1, iy) * tx) * (1 - ty) + (at(ix, iy + 1) * (1 - tx) + at(ix + 1, iy + 1) * tx) * ty;
          o[c] = static_cast<std::uint8_t>(std::lround(linear_to_srgb(v) * 255));
        }
      }
  }
  return out;
}
}  // namespace

TEST(Distortion, FoldedPassMatchesASeparatePass) {
  ASSERT_TRUE(test::gl_ready());
  render::Scene s = test::scene("pattern:noise");
  render::Compositor plain = lens_compositor(480, 270, false);
  render::Compositor folded = lens_compositor(480, 270, true);
  const render::FrameParams p = test::frame(render::Method::full, 1.0);
  const image::Image undistorted = test::render_frame(plain, s, p);
  const image::Image gpu = test::render_frame(folded, s, p);
  const image::Image cpu = distort(undistorted, *DisplayModel::load(test::source_path("data/display/htc_vive_pro_eye_lens.json")));
  EXPECT_GE(image::psnr(cpu, gpu), 40.0);
  // The panel's corners show nothing: the corrected image does not reach them.
  EXPECT_EQ(gpu.at(0, 0)[1], 0);
  EXPECT_GT(gpu.at(120, 135)[0] + gpu.at(120, 135)[1] + gpu.at(120, 135)[2], 0);
}

TEST(Distortion, NoDistortionKeepsTheUndistortedFrame) {
  ASSERT_TRUE(test::gl_ready());
  render::Scene s = test::scene("pattern:noise");
  render::Compositor off = lens_compositor(480, 270, false);
  render::Compositor plainmodel = test::make_compositor(480, 270);
  const render::FrameParams p = test::frame(render::Method::rmfr, 2.0, 0.3, 0.6);
  EXPECT_EQ(image::max_abs_diff(test::render_frame(off, s, p), test::render_frame(plainmodel, s, p)), 0);
}

TEST(Golden, CheckerThroughTheLens) {
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = lens_compositor(480, 270, true);
  render::Scene s = test::scene("pattern:checker");
  test::expect_matches_golden(test::render_frame(c, s, render::efr_frame(render::Method::rmfr, Eye::right, 2.0, 3.0, 0.3, 0.3)),
                              "checker_lens_rmfr");
}

// The inset methods (render/image/src/methods/inset.cpp, docs/methods.md "inset"): an
// outer view at 1/σ per axis and an inner view at full density blended over it. The
// inner view follows the fovea (inset) or stays at the optical centre (inset-fixed); the
// shaded samples follow the buffer-size rule; the blend band has no hard edge. Their
// golden images are made by golden_test.cpp with every other method's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "foveal/image/method_description.hpp"
#include "foveal/rmfr_mapping.hpp"
#include <nlohmann/json.hpp>

#include "gl_support.hpp"
#include "test_support.hpp"

using namespace foveal;
using render::Method;

namespace {

Method method(const char* name) {
  auto m = render::parse_method(name);
  EXPECT_TRUE(m) << name;
  return m ? *m : Method::full;
}

// EFR: σ_d on the right eye, σ_nd on the left; each eye's fovea given (normalised, top-left).
render::FrameParams inset_frame(Method m, double sigma_d, double sigma_nd, glm::dvec2 left, glm::dvec2 right) {
  render::FrameParams p = render::efr_frame(m, Eye::right, sigma_d, sigma_nd, 0.3, 0.3);
  p.eyes[0].fovea_x = left.x, p.eyes[0].fovea_y = left.y;
  p.eyes[1].fovea_x = right.x, p.eyes[1].fovea_y = right.y;
  return p;
}

// PSNR against full of a 40×40 patch of the left eye around (x, y) (normalised, top-left).
double patch_psnr(const render::Compositor& c, const image::Image& full, const image::Image& img, double x, double y) {
  return image::psnr(full, img, test::fovea_patch(c, Eye::left, x, y, 40));
}

}  // namespace

TEST(Inset, IsDescribedAndNamed) {
  EXPECT_STREQ(render::method_name(method("inset")), "inset");
  EXPECT_STREQ(render::method_name(method("inset-fixed")), "inset-fixed");
  EXPECT_TRUE(render::follows_gaze(method("inset")));
  EXPECT_FALSE(render::follows_gaze(method("inset-fixed")));
  EXPECT_NE(render::method_names_joined(",").find("inset,inset-fixed"), std::string::npos);
  // One kernel for both: one set of programs.
  EXPECT_EQ(render::kernel_index(method("inset")), render::kernel_index(method("inset-fixed")));
}

// Outer round(W/σ)×round(H/σ) + inner round(0.35·W)×round(0.35·H) (the default: 35% of
// the tangent extent), the inner view slid inside the view at the edges, its size kept.
TEST(Inset, PlanFollowsTheBufferSizeRule) {
  const EyeFrustum f = DisplayModel{}.eye(Eye::left);
  for (double sigma : {1.5, 2.0, 3.0}) {
    for (glm::dvec2 fovea : {glm::dvec2(0.5, 0.5), glm::dvec2(0.0, 0.0), glm::dvec2(1.0, 0.3)}) {
      render::EyeFoveation e;
      e.sigma = sigma, e.fovea_x = fovea.x, e.fovea_y = fovea.y;
      auto p = render::plan_eye(method("inset"), e, 1440, 1600, f);
      ASSERT_TRUE(p) << p.error().message;
      ASSERT_EQ(p->layers.size(), 2u);
      const render::Layer& in = p->layers[0];
      EXPECT_EQ(in.w, static_cast<int>(std::lround(0.35 * 1440)));
      EXPECT_EQ(in.h, static_cast<int>(std::lround(0.35 * 1600)));
      EXPECT_GE(in.x, 0);
      EXPECT_GE(in.y, 0);
      EXPECT_LE(in.x + in.w, 1440);
      EXPECT_LE(in.y + in.h, 1600);
      const std::size_t outer = static_cast<std::size_t>(rmfr::rmfr_buffer_size(1440, sigma)) *
                                static_cast<std::size_t>(rmfr::rmfr_buffer_size(1600, sigma));
      EXPECT_EQ(p->shaded_samples(), outer + static_cast<std::size_t>(in.w) * static_cast<std::size_t>(in.h)) << sigma;
    }
  }
  // An angle: tan(20°) of half-extent is 2·tan(20°)/(tan_r − tan_l)·W pixels wide.
  render::EyeFoveation e;
  e.sigma = 2, e.inset_deg = 20;
  auto p = render::plan_eye(method("inset"), e, 1440, 1600, f);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->layers[0].w, static_cast<int>(std::lround(2 * std::tan(20 * M_PI / 180) / (f.tan_right - f.tan_left) * 1440)));
  e.inset_deg = -1;
  EXPECT_FALSE(render::plan_eye(method("inset"), e, 1440, 1600, f));
  e.inset_deg = 0, e.inset_band_deg = std::nan("");
  EXPECT_FALSE(render::plan_eye(method("inset"), e, 1440, 1600, f));
}

// The compositor shades what the plans say, both eyes, through both pipelines.
TEST(Inset, ShadedSamplesMatchTheRule) {
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = test::make_compositor(480, 270);
  render::Scene s = test::scene("pattern:noise");
  for (render::Pipeline pipeline : render::all_pipelines()) {
    render::FrameParams p = inset_frame(method("inset"), 2.0, 3.0, {0.3, 0.4}, {0.8, 0.9});
    p.pipeline = pipeline;
    auto t = c.render(s, p);
    ASSERT_TRUE(t) << t.error().message;
    std::size_t expect = 0;
    for (double sigma : {3.0, 2.0}) {  // left (non-dominant), right
      const std::size_t outer = static_cast<std::size_t>(rmfr::rmfr_buffer_size(240, sigma)) *
                                static_cast<std::size_t>(rmfr::rmfr_buffer_size(270, sigma));
      expect += outer + static_cast<std::size_t>(std::lround(0.35 * 240)) * static_cast<std::size_t>(std::lround(0.35 * 270));
    }
    EXPECT_EQ(t->shaded_samples, expect) << render::pipeline_name(pipeline);
    EXPECT_EQ(c.buffer_size(Eye::left)[1], static_cast<int>(std::lround(0.35 * 270)) + rmfr::rmfr_buffer_size(270, 3.0));
  }
}

// The inner view's full-resolution detail is where the fovea is, and moves with it; the
// fixed inset's stays at the centre whatever the fovea. Pixel-scale noise: the outer view
// at σ 4 loses it, the inner view keeps it exactly.
TEST(Inset, TheInnerViewFollowsTheFoveaAndTheFixedOneDoesNot) {
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = test::make_compositor(960, 540);
  render::Scene s = test::scene("pattern:noise");
  for (render::Pipeline pipeline : render::all_pipelines()) {
    render::FrameParams fp = test::frame(Method::full, 1.0);
    fp.pipeline = pipeline;
    const image::Image full = test::render_frame(c, s, fp);
    const glm::dvec2 a(0.25, 0.3), b(0.75, 0.7);
    for (const char* name : {"inset", "inset-fixed"}) {
      const bool tracked = std::string(name) == "inset";
      for (glm::dvec2 fovea : {a, b}) {
        render::FrameParams p = inset_frame(method(name), 4.0, 4.0, fovea, fovea);
        p.pipeline = pipeline;
        const image::Image img = test::render_frame(c, s, p);
        const glm::dvec2 other = fovea == a ? b : a;
        const std::string what = std::string(name) + " " + render::pipeline_name(pipeline) + " fovea " +
                                 std::to_string(fovea.x) + "," + std::to_string(fovea.y);
        const double centre = patch_psnr(c, full, img, 0.5, 0.5);
        if (tracked) {
          EXPECT_GT(patch_psnr(c, full, img, fovea.x, fovea.y), 60) << what;  // the inner view: exact
          EXPECT_LT(patch_psnr(c, full, img, other.x, other.y), 30) << what;  // the outer view there
        } else {
          EXPECT_GT(centre, 60) << what;
          EXPECT_LT(patch_psnr(c, full, img, fovea.x, fovea.y), 30) << what;
        }
      }
    }
  }
}

// The blend band: the inner view's weight w = (I − O) / (F − O), per pixel in linear
// light (I the inset, O the outer view alone, F full), averaged down each column of the
// inner view, rises from 0 outside to 1 inside across the band without a step; with the
// band at 0 it is one step (so the check can fail).
TEST(Inset, TheBlendBandHasNoHardEdge) {
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = test::make_compositor(960, 540, true);
  render::Scene s = test::scene("pattern:noise");
  const int W = c.eye_width(), H = c.height();
  auto render_float = [&](const render::FrameParams& p) {
    auto t = c.render(s, p);
    EXPECT_TRUE(t) << (t ? "" : t.error().message);
    return c.read_float();
  };
  const std::vector<float> full = render_float(test::frame(Method::full, 1.0));
  // The outer view alone: the inner view pushed into the far corner, away from the columns measured.
  const std::vector<float> outer = render_float(inset_frame(method("inset"), 3.0, 3.0, {1.0, 1.0}, {1.0, 1.0}));
  for (double band : {3.0, 0.0}) {
    render::FrameParams p = inset_frame(method("inset"), 3.0, 3.0, {0.5, 0.5}, {0.5, 0.5});
    for (auto& e : p.eyes) e.inset_band_deg = band;
    const std::vector<float> img = render_float(p);
    const render::Layer in = c.plan(Eye::left).layers[0];
    // Columns from 20 left of the inner view's left edge to its middle (left eye), over
    // its middle rows: read_float's rows run from the bottom, the plan's from the top.
    const int bottom = H - in.y - in.h;
    std::vector<double> w;
    for (int x = in.x - 20; x < in.x + in.w / 2; ++x) {
      double num = 0, den = 0;
      for (int y = bottom + in.h / 4; y < bottom + 3 * in.h / 4; ++y)
        for (int ch = 0; ch < 3; ++ch) {
          const std::size_t k = (static_cast<std::size_t>(y) * static_cast<std::size_t>(2 * W) + static_cast<std::size_t>(x)) * 4 + ch;
          const double d = full[k] - outer[k];
          if (std::abs(d) < 0.02) continue;
          num += (img[k] - outer[k]) * d;
          den += d * d;
        }
      ASSERT_GT(den, 0) << x;
      w.push_back(num / den);
    }
    EXPECT_NEAR(w.front(), 0.0, 0.02) << "band " << band;
    EXPECT_NEAR(w.back(), 1.0, 0.02) << "band " << band;
    double max_step = 0, max_fall = 0;
    for (std::size_t i = 1; i < w.size(); ++i) {
      max_step = std::max(max_step, w[i] - w[i - 1]);
      max_fall = std::max(max_fall, w[i - 1] - w[i]);
    }
    if (band > 0) {
      // 3° is ~17 columns here: smoothstep's steepest step is 1.5/17 of the rise.
      EXPECT_LT(max_step, 0.15) << "a hard edge in the band";
      EXPECT_LT(max_fall, 0.02) << "the weight is not monotone across the band";
    } else {
      EXPECT_GT(max_step, 0.9) << "band 0 should be a hard edge";
    }
  }
}

// foveal render --method inset: its shaded samples and layers in --json; a bad extent or
// band is bad input (exit 2, naming the option).
TEST(InsetCli, RendersAndReportsItsSamplesAndRejectsBadExtents) {
  test::TempDir d;
  const std::string base = test::bin("foveal") + " render --scene pattern:checker --size 160x90 --frames 1 --out " + d.path("f.png");
  auto r = test::run(base + " --method inset --fovea-right 0.2,0.5 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["method"], "inset");
  // Right eye 80×90 at σ_d 2: outer 40×45, inner round(0.35·80)×round(0.35·90) = 28×31
  // (0.35·90 is 31.4999… in doubles).
  EXPECT_EQ(j["eyes"]["right"]["shaded_samples"].get<std::size_t>(), 40u * 45u + 28u * 31u);
  EXPECT_EQ(j["eyes"]["right"]["layers"][0]["rect"][0].get<int>(), 2);  // 0.2·80 − 14
  auto fixed = test::run(base + " --method inset-fixed --fovea-right 0.2,0.5 --json");
  ASSERT_EQ(fixed.exit_code, 0) << fixed.err;
  EXPECT_GT(nlohmann::json::parse(fixed.out)["eyes"]["right"]["layers"][0]["rect"][0].get<int>(), 20);
  for (const char* bad : {" --inset-deg 95", " --inset-deg -1", " --inset-band-deg 50", " --inset-band-deg nan"}) {
    auto b = test::run(base + " --method inset" + bad);
    EXPECT_EQ(b.exit_code, 2) << bad << ": " << b.err;
    EXPECT_NE(b.err.find(std::string(bad).substr(1, std::string(bad).find(' ', 1) - 1)), std::string::npos) << b.err;
  }
}

// The compositor's acceptance properties: σ = 1 equals full, the fovea works on every
// border and corner, the dominant eye's half is the sharper one, memory stays bounded.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "foveal/image/kfr_mapping.hpp"
#include "gl_support.hpp"
#include "test_support.hpp"

using namespace foveal;
using render::Method;

namespace {
constexpr int kW = 480, kH = 270;  // side by side: two 240x270 eyes
const double kPositions[9][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0.5, 0}, {0.5, 1}, {0, 0.5}, {1, 0.5}, {0.5, 0.5}};
}  // namespace

TEST(Compositor, SigmaOneMatchesFullWithTheFoveaAnywhere) {
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = test::make_compositor(kW, kH);
  for (const char* spec : {"pattern:noise@20", "data/scenes/WaterBottle/WaterBottle.gltf"}) {
    const std::string path = std::string(spec).rfind("pattern:", 0) == 0 ? spec : test::source_path(spec);
    render::Scene s = test::scene(path);
    const image::Image full = test::render_frame(c, s, test::frame(Method::full, 1.0));
    for (const auto& p : kPositions) {
      const image::Image r = test::render_frame(c, s, test::frame(Method::rmfr, 1.0, p[0], p[1]));
      EXPECT_GE(image::psnr(full, r), 40.0) << spec << " fovea " << p[0] << "," << p[1];
    }
  }
}

TEST(Compositor, FoveaOnCornersBordersAndCentreIsFiniteAndAsSharpAsCentred) {
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = test::make_compositor(kW, kH, true);
  render::Scene s = test::scene("pattern:checker");
  const image::Image full = test::render_frame(c, s, test::frame(Method::full, 1.0));
  auto patch_psnr = [&](double x, double y, double* finite_fraction) {
    const image::Image r = test::render_frame(c, s, test::frame(Method::rmfr, 2.6, x, y));
    const std::vector<float> px = c.read_float();
    std::size_t finite = 0;
    for (float v : px) finite += std::isfinite(v) ? 1 : 0;
    *finite_fraction = static_cast<double>(finite) / static_cast<double>(px.size());
    double worst = INFINITY;
    for (Eye e : kEyes) worst = std::min(worst, image::psnr(full, r, test::fovea_patch(c, e, x, y)));
    return worst;
  };
  double finite = 0;
  const double centre = patch_psnr(0.5, 0.5, &finite);
  EXPECT_EQ(finite, 1.0);
  EXPECT_GT(centre, 20.0);
  for (const auto& p : kPositions) {
    const double q = patch_psnr(p[0], p[1], &finite);
    EXPECT_EQ(finite, 1.0) << "non-finite pixels with the fovea at " << p[0] << "," << p[1];
    EXPECT_GE(q, centre - 1.0) << "fovea " << p[0] << "," << p[1] << ": patch PSNR " << q << " dB vs centred " << centre;
  }
}

TEST(Compositor, EveryMethodIsFiniteWithTheFoveaOnEveryBorderAndCorner) {
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = test::make_compositor(kW, kH, true);
  render::Scene s = test::scene("pattern:noise");
  for (Method m : {Method::kfr, Method::hyperbolic, Method::linear})
    for (const auto& p : kPositions) {
      ASSERT_TRUE(c.render(s, test::frame(m, 2.6, p[0], p[1])));
      std::size_t bad = 0;
      for (float v : c.read_float()) bad += std::isfinite(v) ? 0 : 1;
      EXPECT_EQ(bad, 0u) << render::method_name(m) << " fovea " << p[0] << "," << p[1];
    }
}

TEST(Compositor, KfrSamplesInTheDirectionOfTheAuthorsShaders) {
  // Every texel KFR lights is the full frame's pixel at the texel's source, so the CPU
  // simulation from the reference formulas (image/kfr_mapping.hpp, pinned by
  // tests/image/kfr_mapping_test.cpp) predicts the compositor's image. The opposite
  // direction crowds the buffer around the fovea and misses the prediction by > 15 dB.
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = test::make_compositor(kW, kH);
  render::Scene s = test::scene("pattern:noise");
  const image::Image full = test::render_frame(c, s, test::frame(Method::full, 1.0));
  const int w = c.eye_width();
  for (const auto& p : {std::array<double, 3>{2.6, 0.5, 0.5}, std::array<double, 3>{2.0, 0.3, 0.7}, std::array<double, 3>{3.0, 0.9, 0.1}}) {
    const image::Image kfr = test::render_frame(c, s, test::frame(Method::kfr, p[0], p[1], p[2]));
    for (Eye e : kEyes) {
      const image::Rect half{e == Eye::left ? 0 : w, 0, w, kH};
      const image::Image predicted = image::simulate_kfr(image::crop(full, half), p[0], 4.0, p[1], p[2]);
      EXPECT_GT(image::psnr(image::crop(kfr, half), predicted), 35.0)
          << eye_name(e) << " eye, sigma " << p[0] << ", fovea " << p[1] << "," << p[2];
    }
  }
}

TEST(Compositor, MethodsAtEqualCostAreSharperAtTheFoveaThanAway) {
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = test::make_compositor(kW, kH);
  render::Scene s = test::scene("pattern:noise");
  const image::Image full = test::render_frame(c, s, test::frame(Method::full, 1.0));
  for (Method m : {Method::rmfr, Method::kfr, Method::hyperbolic, Method::linear}) {
    const image::Image img = test::render_frame(c, s, test::frame(m, 2.0, 0.5, 0.5));
    const double fovea = image::psnr(full, img, test::fovea_patch(c, Eye::left, 0.5, 0.5, 32));
    const double corner = image::psnr(full, img, image::Rect{0, 0, 32, 32});
    EXPECT_GT(fovea, corner + 3.0) << render::method_name(m);
    // Equal cost: both eyes' lighting passes shade about 2·W·H/σ² samples.
    const double shaded = double(c.plan(Eye::left).shaded_samples() + c.plan(Eye::right).shaded_samples());
    EXPECT_NEAR(shaded / (2.0 * (kW / 2) * kH / 4.0), 1.0, 0.03) << render::method_name(m);
  }
}

// The plans are top-left and the shaders GL's bottom-left: the one flip between them
// (method_binding.cpp) puts each method's sharp region where the fovea is, near the
// top, and not at its mirror image near the bottom.
TEST(Compositor, EveryGazeMethodIsSharpWhereTheTopLeftFoveaIs) {
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = test::make_compositor(kW, kH);
  render::Scene s = test::scene("pattern:noise");
  const image::Image full = test::render_frame(c, s, test::frame(Method::full, 1.0));
  const double x = 0.25, y = 0.2;
  for (Method m : render::all_methods()) {
    if (!render::follows_gaze(m)) continue;
    const image::Image img = test::render_frame(c, s, test::frame(m, 3.0, x, y));
    for (Eye e : kEyes) {
      const double at = image::psnr(full, img, test::fovea_patch(c, e, x, y, 24));
      const double mirror = image::psnr(full, img, test::fovea_patch(c, e, x, 1.0 - y, 24));
      EXPECT_GT(at, mirror + 1.0) << render::method_name(m) << " " << eye_name(e) << ": " << at << " dB at the fovea, "
                                  << mirror << " dB at its mirror";
    }
  }
}

TEST(Compositor, NonFiniteFoveaFallsBackToTheCentre) {
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = test::make_compositor(kW, kH);
  render::Scene s = test::scene("pattern:noise");
  const image::Image centred = test::render_frame(c, s, test::frame(Method::rmfr, 2.0));
  const image::Image nan = test::render_frame(c, s, test::frame(Method::rmfr, 2.0, NAN, INFINITY));
  EXPECT_EQ(image::max_abs_diff(centred, nan), 0);
  EXPECT_FALSE(c.render(s, test::frame(Method::rmfr, 0.5)));
  EXPECT_FALSE(c.render(s, test::frame(Method::rmfr, NAN)));
}

TEST(Compositor, UnknownMethodIsAnErrorNotAnotherMethodsKernel) {
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = test::make_compositor(kW, kH);
  render::Scene s = test::scene("pattern:noise");
  for (double sigma : {1.0, 2.0}) {
    auto r = c.render(s, test::frame(static_cast<Method>(42), sigma));
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("unknown foveation method"), std::string::npos) << r.error().message;
  }
  EXPECT_TRUE(c.render(s, test::frame(Method::kfr, 2.0)));  // and the compositor still works
}

TEST(Compositor, SwappingTheDominantEyeSwapsTheSharperHalf) {
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = test::make_compositor(kW, kH);
  render::Scene s = test::scene("pattern:noise@15");
  const image::Image full = test::render_frame(c, s, test::frame(Method::full, 1.0));
  const int w = c.eye_width();
  // Peripheral PSNR of each half: the whole half minus the central fovea patch.
  auto periphery = [&](const image::Image& img, Eye e) {
    const int x0 = e == Eye::left ? 0 : w;
    double sum = 0;
    std::size_t n = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < w; ++x) {
        if (std::abs(x - w / 2) < 40 && std::abs(y - kH / 2) < 40) continue;
        for (int ch = 0; ch < 3; ++ch) {
          const double d = double(img.at(x0 + x, y)[ch]) - double(full.at(x0 + x, y)[ch]);
          sum += d * d;
          ++n;
        }
      }
    return 10 * std::log10(255.0 * 255.0 / (sum / double(n)));
  };
  for (Eye dominant : kEyes) {
    const image::Image img = test::render_frame(c, s, render::efr_frame(Method::rmfr, dominant, 1.6, 3.0, 0.3, 0.3));
    const Eye other = dominant == Eye::left ? Eye::right : Eye::left;
    EXPECT_GT(periphery(img, dominant), periphery(img, other) + 1.0) << "dominant " << eye_name(dominant);
    EXPECT_EQ(c.buffer_size(dominant)[0], 150);
    EXPECT_EQ(c.buffer_size(other)[0], 80);
  }
}

TEST(Compositor, RenderTargetsStayUnder200MBAtFullSize) {
  ASSERT_TRUE(test::gl_ready());
  render::CompositorOptions o;  // 2880x1600, 2048² shadow map
  auto c = render::Compositor::create(o, test::source_shaders());
  ASSERT_TRUE(c) << c.error().message;
  render::Scene s = test::scene("pattern:checker");
  // σ = 1 is the largest: transformed buffers as big as the G-buffer.
  ASSERT_TRUE(c->render(s, test::frame(Method::rmfr, 1.0)));
  const double worst = static_cast<double>(c->memory().total()) / 1e6;
  EXPECT_LE(worst, 200.0);
  ASSERT_TRUE(c->render(s, render::efr_frame(Method::rmfr, Eye::right, 2.0, 3.0, 0.3, 0.3)));
  EXPECT_LT(static_cast<double>(c->memory().total()) / 1e6, worst);
  EXPECT_EQ(c->buffer_size(Eye::right)[0], 720);
  EXPECT_EQ(c->buffer_size(Eye::left)[1], 533);
}

TEST(Compositor, DungeonFromInsideTheRoomFillsTheView) {
  ASSERT_TRUE(test::gl_ready());
  render::Compositor c = test::make_compositor(640, 360);
  render::Scene s = test::scene(test::source_path("data/scenes/Dungeon/dungeon_simplified.gltf"));
  const image::Image img = test::render_frame(c, s, render::efr_frame(Method::rmfr, Eye::right, 2.0, 3.0, 0.3, 0.3));
  // The background colour shows only where no geometry is.
  std::size_t background = 0, lit = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const std::uint8_t* p = img.at(x, y);
      if (std::abs(p[0] - 40) < 6 && std::abs(p[1] - 44) < 6 && std::abs(p[2] - 52) < 6) ++background;
      if (p[0] + p[1] + p[2] > 60) ++lit;
    }
  const double n = static_cast<double>(img.width) * img.height;
  EXPECT_LT(static_cast<double>(background) / n, 0.35);  // the corridor has no roof: sky above the walls
  EXPECT_GT(static_cast<double>(lit) / n, 0.5);
}

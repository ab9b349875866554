// foveal-rmfr on the CPU: plans, EFR, automatic f, the GLSL text.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "foveal/image/auto_f.hpp"
#include "foveal/rmfr.hpp"
#include "foveal/rmfr_mapping.hpp"

using namespace foveal;

namespace {
rmfr::EyeParams eye(double sigma, double x = 0.5, double y = 0.5) {
  rmfr::EyeParams e;
  e.width = 1440, e.height = 1600, e.sigma = sigma, e.fovea = {x, y};
  return e;
}
}  // namespace

TEST(RmfrPlan, BufferSizeFAndFoveaFromTheEye) {
  auto p = rmfr::plan_eye(eye(2.6, 0.25, 0.1));
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ(p->screen_w, 1440);
  EXPECT_EQ(p->buffer_w, 554);
  EXPECT_EQ(p->buffer_h, 615);
  EXPECT_EQ(p->fx, 0.3);
  EXPECT_DOUBLE_EQ(p->fovea_x, 0.25);
  EXPECT_DOUBLE_EQ(p->fovea_y, 0.9);  // top-left in, GL frame out
  EXPECT_EQ(p->shaded_samples(), 554u * 615u);
}

TEST(RmfrPlan, SigmaOneIsFullRateWithoutWarp) {
  auto p = rmfr::plan_eye(eye(1.0, 0.1, 0.9));
  ASSERT_TRUE(p);
  EXPECT_EQ(p->buffer_w, 1440);
  EXPECT_EQ(p->buffer_h, 1600);
  EXPECT_EQ(p->fx, rmfr::kRmfrIdentityF);
  EXPECT_EQ(p->fy, rmfr::kRmfrIdentityF);
}

TEST(RmfrPlan, NonFiniteFoveaIsCentredAndOutsideIsClamped) {
  auto p = rmfr::plan_eye(eye(2.0, NAN, 7.0));
  ASSERT_TRUE(p);
  EXPECT_EQ(p->fovea_x, 0.5);
  EXPECT_EQ(p->fovea_y, 0.0);
}

TEST(RmfrPlan, BadInputIsRefusedWithWhatIsWrong) {
  rmfr::EyeParams e = eye(0.5);
  auto p = rmfr::plan_eye(e);
  ASSERT_FALSE(p);
  EXPECT_EQ(p.error().kind, ErrorKind::bad_input);
  EXPECT_NE(p.error().message.find("sigma"), std::string::npos);
  e = eye(NAN);
  EXPECT_FALSE(rmfr::plan_eye(e));
  e = eye(2.0), e.fx = 0;
  EXPECT_FALSE(rmfr::plan_eye(e));
  e = eye(2.0), e.fy = INFINITY;
  EXPECT_FALSE(rmfr::plan_eye(e));
  e = eye(2.0), e.width = 0;
  EXPECT_NE(rmfr::plan_eye(e).error().message.find("viewport"), std::string::npos);
  e = eye(2.0), e.frustum.tan_left = 2;
  EXPECT_NE(rmfr::plan_eye(e).error().message.find("frustum"), std::string::npos);
}

TEST(RmfrPlan, EfrPutsTheDominantEyeAtSigmaD) {
  rmfr::EfrSettings s;
  s.sigma_d = 2.0, s.sigma_nd = 3.0, s.dominant_eye = 0, s.fx = 0.25, s.fy = 0.35;
  auto p = rmfr::plan_efr(s, {eye(9), eye(9)});
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ((*p)[0].buffer_w, 720);
  EXPECT_EQ((*p)[1].buffer_w, 480);
  EXPECT_EQ((*p)[0].fx, 0.25);
  EXPECT_EQ((*p)[1].fy, 0.35);
  s.dominant_eye = 1;
  p = rmfr::plan_efr(s, {eye(1), eye(1)});
  ASSERT_TRUE(p);
  EXPECT_EQ((*p)[0].buffer_w, 480);
  EXPECT_EQ((*p)[1].buffer_w, 720);
}

TEST(RmfrPlan, EfrRefusesASwappedPairAndAnUnknownEye) {
  rmfr::EfrSettings s;
  s.sigma_d = 3.0, s.sigma_nd = 2.0;
  EXPECT_NE(rmfr::plan_efr(s, {eye(1), eye(1)}).error().message.find("sigma_nd"), std::string::npos);
  s = {};
  s.dominant_eye = 2;
  EXPECT_FALSE(rmfr::plan_efr(s, {eye(1), eye(1)}));
  s = {};
  auto bad = eye(1);
  bad.height = -1;
  auto p = rmfr::plan_efr(s, {eye(1), bad});
  ASSERT_FALSE(p);
  EXPECT_EQ(p.error().message.rfind("right eye: ", 0), 0u) << p.error().message;
}

TEST(RmfrAutoF, MatchesTheImageSpaceSearchAndRefusesBadFrames) {
  // Horizontal detail only: the search should warp x less than y... here just: the
  // library's answer is the image-space search's on the same pixels, bottom-up too.
  image::Image full(64, 32);
  for (int y = 0; y < full.height; ++y)
    for (int x = 0; x < full.width; ++x) {
      std::uint8_t* p = full.at(x, y);
      p[0] = static_cast<std::uint8_t>((x * 37) % 256), p[1] = static_cast<std::uint8_t>((y * 11) % 256), p[2] = 90, p[3] = 255;
    }
  image::MetricsOptions mo;
  mo.ppd = 10;
  mo.fovea = {0.3, 0.4}, mo.fovea_right = {0.6, 0.5};
  auto want = image::estimate_rmfr_f(full, {2.0, 3.0}, mo);
  ASSERT_TRUE(want);
  rmfr::ImageView v{full.rgba.data(), full.width, full.height, 0, false};
  auto got = rmfr::estimate_f(v, {2.0, 3.0}, {{{0.3, 0.4}, {0.6, 0.5}}}, 10);
  ASSERT_TRUE(got) << got.error().message;
  EXPECT_EQ(got->fx, want->fx);
  EXPECT_EQ(got->fy, want->fy);
  EXPECT_GE(got->fx, 0.05);
  EXPECT_LE(got->fx, 1.0);
  // The same frame bottom row first.
  std::vector<std::uint8_t> flipped(full.rgba.size());
  const std::size_t row = static_cast<std::size_t>(full.width) * 4;
  for (int y = 0; y < full.height; ++y) std::copy_n(full.at(0, full.height - 1 - y), row, flipped.data() + y * row);
  auto up = rmfr::estimate_f({flipped.data(), full.width, full.height, row, true}, {2.0, 3.0}, {{{0.3, 0.4}, {0.6, 0.5}}}, 10);
  ASSERT_TRUE(up);
  EXPECT_EQ(up->fx, want->fx);

  EXPECT_FALSE(rmfr::estimate_f({nullptr, 64, 32, 0, false}, {2, 2}, {}, 10));
  EXPECT_FALSE(rmfr::estimate_f({full.rgba.data(), 63, 32, 0, false}, {2, 2}, {}, 10));
  EXPECT_FALSE(rmfr::estimate_f({full.rgba.data(), 64, 32, 8, false}, {2, 2}, {}, 10));
  EXPECT_FALSE(rmfr::estimate_f(v, {0.5, 2}, {}, 10));
  EXPECT_FALSE(rmfr::estimate_f(v, {2, 2}, {}, 0));
}

TEST(RmfrGlsl, SourceIsSelfContainedAndFilesAreFound) {
  const std::string src(rmfr::glsl_source());
  EXPECT_EQ(src.find("#include"), std::string::npos);
  for (const char* name : {"foveal_rmfr_forward", "foveal_rmfr_screen_pixel", "foveal_rmfr_eccentricity_deg", "foveal_rmfr_footprint"})
    EXPECT_NE(src.find(name), std::string::npos) << name;
  EXPECT_NE(rmfr::glsl_file("foveal/rmfr.glsl").find("#include \"foveal/rmfr_mapping.glsl\""), std::string::npos);
  EXPECT_FALSE(rmfr::glsl_file("foveal/rmfr_mapping.glsl").empty());
  EXPECT_TRUE(rmfr::glsl_file("common/mapping.glsl").empty());
  EXPECT_TRUE(std::filesystem::exists(rmfr::glsl_directory() + "/foveal/rmfr.glsl")) << rmfr::glsl_directory();
  EXPECT_STREQ(rmfr::version(), "0.3.0");
}

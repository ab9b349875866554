// foveal metrics from the command line: JSON, stereo, exit codes.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "foveal/image/image.hpp"
#include "test_support.hpp"

using namespace foveal;

namespace {

image::Image gradient(int w, int h, int offset) {
  image::Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = img.at(x, y);
      p[0] = static_cast<std::uint8_t>((x * 5 + offset) % 256);
      p[1] = static_cast<std::uint8_t>((y * 7) % 256);
      p[2] = static_cast<std::uint8_t>(((x ^ y) + offset) % 256);
      p[3] = 255;
    }
  return img;
}

std::string metrics(const std::string& args) { return test::bin("foveal") + " metrics " + args; }

}  // namespace

TEST(MetricsCli, IdenticalImagesPrintInfAsAString) {
  test::TempDir d;
  ASSERT_TRUE(image::save_png(d.path("a.png"), gradient(64, 40, 0)));
  auto r = test::run(metrics("--ref " + d.path("a.png") + " --test " + d.path("a.png") + " --fovea 0.5,0.5 --json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["psnr_db"], "inf");
  EXPECT_EQ(j["fpsnr_db"], "inf");
  EXPECT_EQ(j["ssim"].get<double>(), 1.0);
  EXPECT_EQ(j["stereo"], false);
}

TEST(MetricsCli, StereoReportsEachEyeAndTheCombination) {
  test::TempDir d;
  ASSERT_TRUE(image::save_png(d.path("a.png"), gradient(96, 40, 0)));
  ASSERT_TRUE(image::save_png(d.path("b.png"), gradient(96, 40, 3)));
  auto r = test::run(metrics("-r " + d.path("a.png") + " -t " + d.path("b.png") +
                             " --stereo --fovea 0.2,0.3 --fovea-right 0.8,0.6 --ppd 20 --json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* k : {"left", "right"}) {
    EXPECT_GT(j[k]["psnr_db"].get<double>(), 0.0) << k;
    EXPECT_LT(j[k]["ssim"].get<double>(), 1.0) << k;
    EXPECT_GT(j[k]["fpsnr_db"].get<double>(), 0.0) << k;
  }
  EXPECT_GT(j["fpsnr_db"].get<double>(), 0.0);
  EXPECT_EQ(j["fovea_right"][0].get<double>(), 0.8);
  EXPECT_EQ(j["ppd"].get<double>(), 20.0);
  auto text = test::run(metrics("-r " + d.path("a.png") + " -t " + d.path("b.png") + " --stereo --fovea 0.5,0.5"));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("combined"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("FPSNR"), std::string::npos) << text.out;
}

TEST(MetricsCli, BadInputsExitTwoNamingTheFile) {
  test::TempDir d;
  ASSERT_TRUE(image::save_png(d.path("a.png"), gradient(64, 40, 0)));
  ASSERT_TRUE(image::save_png(d.path("small.png"), gradient(60, 40, 0)));
  const std::string a = " --fovea 0.5,0.5 --ref " + d.path("a.png");
  auto missing = test::run(metrics(a + " --test " + d.path("nope.png")));
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("nope.png"), std::string::npos) << missing.err;
  auto missing_ref = test::run(metrics("--fovea 0.5,0.5 --ref " + d.path("gone.png") + " --test " + d.path("a.png")));
  EXPECT_EQ(missing_ref.exit_code, 2);
  EXPECT_NE(missing_ref.err.find("gone.png"), std::string::npos) << missing_ref.err;
  auto size = test::run(metrics(a + " --test " + d.path("small.png")));
  EXPECT_EQ(size.exit_code, 2);
  EXPECT_NE(size.err.find("small.png"), std::string::npos) << size.err;
  EXPECT_NE(size.err.find("60x40"), std::string::npos) << size.err;
  EXPECT_EQ(test::run(metrics("--ref " + d.path("a.png") + " --test " + d.path("a.png") + " --fovea 1.5,0")).exit_code, 2);
  EXPECT_EQ(test::run(metrics(a + " --test " + d.path("a.png") + " --ppd 0")).exit_code, 2);
  EXPECT_EQ(test::run(metrics(a + " --test " + d.path("a.png") + " --fovea-right 0.5,0.5")).exit_code, 2);
  EXPECT_EQ(test::run(metrics("--ref " + d.path("a.png") + " --test " + d.path("a.png"))).exit_code, 2);  // no --fovea
  auto help = test::run(metrics("--help"));
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("--fovea-right"), std::string::npos);
}

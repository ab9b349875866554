// foveal metrics from the command line: JSON, stereo (given or detected), the one ppd of a
// call, display models by name, exit codes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

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

nlohmann::json metrics_json(const std::string& args) {
  auto r = test::run(metrics(args + " --json"));
  EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
  return r.exit_code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json::object();
}

// The pixels per degree at the centre of an eye of `eye_w` px showing the HTC Vive Pro
// Eye's field (focal 753.6 px at 1440 px): 13.153 at its own size.
double vive_ppd(int eye_w) { return 1.0 / (2.0 * std::atan(0.5 / (753.6 * eye_w / 1440.0)) * 180.0 / std::numbers::pi); }

// A 2880x1600 pair, the size `foveal render` writes for the default display: the test
// differs from the reference only in a 40x40 patch around (0.4, 0.5) of the left eye.
void write_side_by_side_pair(const test::TempDir& d) {
  image::Image ref = gradient(2880, 1600, 0), test = ref;
  for (int y = 780; y < 820; ++y)
    for (int x = 556; x < 596; ++x) test.at(x, y)[0] = static_cast<std::uint8_t>(test.at(x, y)[0] ^ 0x80);
  ASSERT_TRUE(image::save_png(d.path("full.png"), ref));
  ASSERT_TRUE(image::save_png(d.path("rmfr.png"), test));
}

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

// Issue 39, item 6: a side-by-side frame of the display's size was one image unless
// --stereo: --fovea 0.4,0.5 then fell in the left eye's right part, and no eye was
// reported. Now such a frame is detected as stereo (--mono overrides), and says so.
TEST(MetricsCli, AFrameOfTheDisplaysSideBySideSizeIsStereoWithTheFoveaInTheLeftEye) {
  test::TempDir d;
  write_side_by_side_pair(d);
  const std::string io = "--ref " + d.path("full.png") + " --test " + d.path("rmfr.png");
  auto j = metrics_json(io + " --fovea 0.4,0.5");
  EXPECT_EQ(j["stereo"], true);
  EXPECT_EQ(j["stereo_from"], "detected");
  EXPECT_EQ(j["display"], "htc_vive_pro_eye");
  EXPECT_NEAR(j["ppd"].get<double>(), vive_ppd(1440), 1e-5);  // the model's float tangents
  EXPECT_EQ(j["fovea_left"][0].get<double>(), 0.4);
  EXPECT_EQ(j["right"]["psnr_db"], "inf");  // the error is in the left eye only
  // The fovea at the error weighs it up in the left eye; an eye's width away, down.
  ASSERT_TRUE(j["left"]["fpsnr_db"].is_number()) << j;
  EXPECT_LT(j["left"]["fpsnr_db"].get<double>(), j["left"]["psnr_db"].get<double>() - 3);
  auto away = metrics_json(io + " --fovea 0.95,0.5");
  EXPECT_GT(away["left"]["fpsnr_db"].get<double>(), away["left"]["psnr_db"].get<double>() + 3);
  // --stereo gives the same figures; the source differs.
  auto given = metrics_json(io + " --fovea 0.4,0.5 --stereo");
  EXPECT_EQ(given["stereo_from"], "--stereo");
  EXPECT_EQ(given["left"], j["left"]);
  // --mono: one image, its fovea 0.4 of the whole width, the ppd of the whole frame as an eye.
  auto mono = metrics_json(io + " --fovea 0.4,0.5 --mono");
  EXPECT_EQ(mono["stereo"], false);
  EXPECT_EQ(mono["stereo_from"], "--mono");
  EXPECT_FALSE(mono.contains("left"));
  EXPECT_NEAR(mono["ppd"].get<double>(), vive_ppd(2880), 1e-5);  // the model's float tangents
  EXPECT_NE(mono["fpsnr_db"], j["fpsnr_db"]);
  auto text = test::run(metrics(io + " --fovea 0.4,0.5"));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("(2880x1600, stereo (detected: 2880x1600 is htc_vive_pro_eye's two eyes side by side; --mono for "
                          "one image), 13.15 ppd (htc_vive_pro_eye's eye at 1440x1600), fovea L 0.400,0.500 R 0.400,0.500)"),
            std::string::npos)
      << text.out;
  EXPECT_NE(test::run(metrics(io + " --fovea 0.4,0.5 --stereo --mono")).exit_code, 0);
}

// Other sizes stay one image unless --stereo, and --fovea-right says why it is refused.
TEST(MetricsCli, OtherSizesAreOneImageUnlessStereo) {
  test::TempDir d;
  ASSERT_TRUE(image::save_png(d.path("a.png"), gradient(96, 40, 0)));
  ASSERT_TRUE(image::save_png(d.path("b.png"), gradient(96, 40, 3)));
  const std::string io = "--ref " + d.path("a.png") + " --test " + d.path("b.png") + " --fovea 0.5,0.5";
  auto j = metrics_json(io);
  EXPECT_EQ(j["stereo"], false);
  EXPECT_EQ(j["stereo_from"], "detected");
  EXPECT_NEAR(j["ppd"].get<double>(), vive_ppd(96), 1e-5);  // the model's float tangents
  auto right = test::run(metrics(io + " --fovea-right 0.5,0.5"));
  EXPECT_EQ(right.exit_code, 2);
  EXPECT_NE(right.err.find("--fovea-right: only for a stereo frame, and this 96x40 frame is one image (detected: not "
                           "htc_vive_pro_eye's side-by-side size nor foveal render's default; --stereo for two eyes)"),
            std::string::npos)
      << right.err;
  auto stereo = metrics_json(io + " --stereo --fovea-right 0.5,0.5");
  EXPECT_EQ(stereo["stereo"], true);
  EXPECT_NEAR(stereo["ppd"].get<double>(), vive_ppd(48), 1e-5);  // the model's float tangents
}

// `metrics --display NAME` resolves NAME as `bench --display` does (data/display/NAME.json).
TEST(MetricsCli, ADisplayByNameAsInBench) {
  test::TempDir d;
  ASSERT_TRUE(image::save_png(d.path("a.png"), gradient(96, 64, 0)));
  ASSERT_TRUE(image::save_png(d.path("b.png"), gradient(96, 64, 3)));
  const std::string io = "--ref " + d.path("a.png") + " --test " + d.path("b.png");
  for (const char* jod : {"", " --jod"}) {
    SCOPED_TRACE(jod);
    auto hires = metrics_json(io + jod + " --fovea 0.5,0.5 --display hires_3800_35ppd");
    EXPECT_EQ(hires["display"], "hires_3800_35ppd");
    EXPECT_NEAR(hires["ppd"].get<double>(), 35.0 * 96 / 3800, 0.001);  // 35 ppd across 3800 px
    auto vive = metrics_json(io + jod + " --fovea 0.5,0.5 --display htc_vive_pro_eye");
    EXPECT_EQ(vive["display"], "htc_vive_pro_eye");
    auto path = metrics_json(io + jod + " --fovea 0.5,0.5 --display " + test::source_path("data/display/hires_3800_35ppd.json"));
    EXPECT_EQ(path["ppd"], hires["ppd"]);
    auto none = test::run(metrics(io + jod + " --fovea 0.5,0.5 --display no_such_headset"));
    EXPECT_EQ(none.exit_code, 2);
    EXPECT_NE(none.err.find("--display no_such_headset: "), std::string::npos) << none.err;
    EXPECT_NE(none.err.find("no_such_headset.json"), std::string::npos) << none.err;
    EXPECT_NE(none.err.find("bundled: hires_3800_35ppd, htc_vive_pro_eye, htc_vive_pro_eye_lens"), std::string::npos) << none.err;
  }
}

// Issue 39, item 6: JOD took the display's eye scaled to the image (5.85 ppd on a 640 px
// eye) while FPSNR took --ppd's 13.15. Every metric of a call now uses one ppd: the
// display's eye at the image's size, or --ppd for all of them.
TEST(MetricsCli, PsnrSsimFpsnrAndJodUseTheSamePpd) {
  test::TempDir d;
  ASSERT_TRUE(image::save_png(d.path("a.png"), gradient(640, 360, 0)));
  ASSERT_TRUE(image::save_png(d.path("b.png"), gradient(640, 360, 5)));
  write_side_by_side_pair(d);
  struct Pair {
    std::string io;
    double ppd;
  } pairs[] = {{"--ref " + d.path("a.png") + " --test " + d.path("b.png"), vive_ppd(640)},  // 5.85
               {"--ref " + d.path("full.png") + " --test " + d.path("rmfr.png"), vive_ppd(1440)}};
  for (const Pair& p : pairs) {
    SCOPED_TRACE(p.io);
    auto plain = metrics_json(p.io + " --fovea 0.4,0.5");
    auto jod = metrics_json(p.io + " --fovea 0.4,0.5 --jod");
    EXPECT_NEAR(plain["ppd"].get<double>(), p.ppd, 1e-5);
    EXPECT_EQ(plain["ppd"], jod["ppd"]);
    EXPECT_EQ(plain["stereo"], jod["stereo"]);
    EXPECT_EQ(jod["ppd_from"], "display");
    auto given = metrics_json(p.io + " --fovea 0.4,0.5 --ppd 20");
    auto given_jod = metrics_json(p.io + " --fovea 0.4,0.5 --ppd 20 --jod");
    EXPECT_EQ(given["ppd"].get<double>(), 20.0);
    EXPECT_NEAR(given_jod["ppd"].get<double>(), 20.0, 1e-4);  // the geometry's float tangents
    EXPECT_EQ(given_jod["ppd_from"], "--ppd");
    EXPECT_NE(given_jod["jod"], jod["jod"]);
  }
  EXPECT_NEAR(vive_ppd(640), 5.85, 0.005);
  auto both = test::run(metrics(pairs[0].io + " --fovea 0.5,0.5 --ppd 20 --display htc_vive_pro_eye"));
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_NE(both.err.find("--ppd: not with --display"), std::string::npos) << both.err;
}

// `foveal calibrate --answers` end to end: scripts in, profiles out.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "foveal/core/gaze_log.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

class CalibrateCli : public ::testing::Test {
 protected:
  test::RunResult calibrate(const std::string& script, const std::string& args) {
    test::write_file(dir_.path("answers.txt"), script);
    return test::run("XDG_CONFIG_HOME=" + dir_.path() + " " + test::bin("foveal") + " calibrate --answers " +
                     dir_.path("answers.txt") + " " + args);
  }
  nlohmann::json profile(const std::string& name) {
    return nlohmann::json::parse(test::read_file(dir_.path("foveal/profiles/" + name + ".json")));
  }
  test::TempDir dir_;
};

struct Script {
  const char* name;
  const char* answers;
  const char* eye;
  double sigma_d, sigma_nd;
};

class CalibrateScripts : public CalibrateCli, public ::testing::WithParamInterface<Script> {};

TEST_P(CalibrateScripts, ProduceTheExpectedProfile) {
  const Script& s = GetParam();
  auto r = calibrate(s.answers, "--profile p --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = profile("p");
  EXPECT_EQ(j["dominant_eye"], s.eye);
  EXPECT_DOUBLE_EQ(j["sigma_d"].get<double>(), s.sigma_d);
  EXPECT_DOUBLE_EQ(j["sigma_nd"].get<double>(), s.sigma_nd);
  EXPECT_EQ(nlohmann::json::parse(r.out)["saved"], true);
}

INSTANTIATE_TEST_SUITE_P(
    Users, CalibrateScripts,
    ::testing::Values(
        Script{"efr_seed_right", "right right right\nd d d d d same\nsame same same same same different\ns s s\n", "right", 2.0, 3.0},
        Script{"left_sensitive", "# a careful left-eye-dominant user\nl l l\nd d d d d d d same\ndifferent\ns s s\n", "left", 1.6, 1.6},
        Script{"tolerant_majority_right", "r l r\nsame\ns s s s s s s s s s d\ns d s\n", "right", 3.0, 5.0}),
    [](const auto& param_info) { return std::string(param_info.param.name); });

TEST_F(CalibrateCli, KeepsTheProfilesOtherSettings) {
  std::filesystem::create_directories(dir_.path("foveal/profiles"));
  test::write_file(dir_.path("foveal/profiles/q.json"), R"({"f_x": 0.25, "ipd_mm": 66})");
  auto r = calibrate("l l l same different s s s", "--profile q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = profile("q");
  EXPECT_DOUBLE_EQ(j["f_x"].get<double>(), 0.25);
  EXPECT_DOUBLE_EQ(j["ipd_mm"].get<double>(), 66.0);
  EXPECT_EQ(j["dominant_eye"], "left");
}

TEST_F(CalibrateCli, FailedValidationSavesNothing) {
  auto r = calibrate("r r r same different d d s", "--profile p");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("calibration rejected"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir_.path("foveal/profiles/p.json")));
}

TEST_F(CalibrateCli, BadScriptsNameTheLine) {
  auto r = calibrate("r r r\nsame\nmaybe\n", "--profile p");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("answers.txt:3"), std::string::npos) << r.err;
  r = calibrate("r r r\nleft\n", "--profile p");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("sigma_uniform"), std::string::npos) << r.err;
  r = calibrate("r r\n", "--profile p");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("answers ended"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir_.path("foveal/profiles/p.json")));
}


// A gaze log of the validation trials: `seconds` at 120 Hz, both eyes fixating straight
// ahead with a known offset (the left eye offset_deg up and right, the right eye
// 1.5 x offset_deg down and left), alternating +-jitter_deg in azimuth from sample to
// sample; every 20th left sample lost.
void write_validation_log(const std::string& path, double seconds, double offset_deg, double jitter_deg) {
  GazeLogHeader h;
  h.rate_hz = 120;
  auto w = GazeLogWriter::create(path, h);
  ASSERT_TRUE(w) << w.error().message;
  auto direction = [](double offset, double toward_deg, double jitter) {
    const double a = offset * std::numbers::pi / 180, t = toward_deg * std::numbers::pi / 180;
    const double az = std::atan(std::tan(a) * std::cos(t)) + jitter * std::numbers::pi / 180;
    const double el = std::asin(std::sin(a) * std::sin(t));
    return glm::vec3(static_cast<float>(std::cos(el) * std::sin(az)), static_cast<float>(std::sin(el)),
                     static_cast<float>(-std::cos(el) * std::cos(az)));
  };
  const int n = static_cast<int>(seconds * 120);
  for (int i = 0; i < n; ++i) {
    GazeSample s;
    s.t_ns = static_cast<TimeNs>(i) * 1'000'000'000 / 120;
    const double j = i % 2 ? jitter_deg : -jitter_deg;
    s.eyes[0] = {kValidDirection, direction(offset_deg, 45, j)};
    s.eyes[1] = {kValidDirection, direction(1.5 * offset_deg, 225, j)};
    if (i % 20 == 0) s.eyes[0] = {};
    ASSERT_TRUE(w->write(s));
  }
  ASSERT_TRUE(w->commit());
}

TEST_F(CalibrateCli, ValidationGazeGoesIntoTheProfile) {
  write_validation_log(dir_.path("gaze.csv"), 3.0, 0.6, 0.05);
  auto r = calibrate("right right right\nd d d d d same\nsame same same same same different\ns s s\n",
                     "--profile p --gaze-log " + dir_.path("gaze.csv") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto g = profile("p")["gaze_quality"];
  EXPECT_EQ(g, nlohmann::json::parse(r.out)["gaze_quality"]);
  EXPECT_EQ(g["targets"], 1);
  EXPECT_EQ(g["source"], dir_.path("gaze.csv"));
  // Accuracy: the offsets, within the 0.05 deg the issue asks (the jitter averages out).
  EXPECT_NEAR(g["left"]["accuracy_deg"].get<double>(), 0.6, 0.05);
  EXPECT_NEAR(g["right"]["accuracy_deg"].get<double>(), 0.9, 0.05);
  // Precision: successive samples 0.1 deg apart in azimuth (a lost sample breaks a pair);
  // STD of +-0.05: 0.05.
  EXPECT_NEAR(g["right"]["rms_s2s_deg"].get<double>(), 0.1, 0.005);
  EXPECT_NEAR(g["left"]["rms_s2s_deg"].get<double>(), 0.1, 0.005);
  EXPECT_NEAR(g["right"]["std_deg"].get<double>(), 0.05, 0.003);
  EXPECT_NEAR(g["left"]["data_loss_pct"].get<double>(), 5.0, 0.2);
  EXPECT_NEAR(g["right"]["data_loss_pct"].get<double>(), 0.0, 0.2);

  // A later calibration without gaze keeps the figures; the profile still loads.
  r = calibrate("right right right\nd d d d d same\nsame same same same same different\ns s s\n", "--profile p");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(profile("p")["gaze_quality"], g);
  const auto show = test::run("XDG_CONFIG_HOME=" + dir_.path() + " " + test::bin("foveal") + " profile show p");
  EXPECT_EQ(show.exit_code, 0) << show.err;

  // A missing log stops the command before anything is saved.
  r = calibrate("r r r same different s s s", "--profile q --gaze-log " + dir_.path("none.csv"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("none.csv"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir_.path("foveal/profiles/q.json")));
}

TEST_F(CalibrateCli, ProfileGazeQualityIsCheckedOnLoad) {
  std::filesystem::create_directories(dir_.path("foveal/profiles"));
  test::write_file(dir_.path("foveal/profiles/b.json"), R"({"gaze_quality": {"left": {"accuracy_deg": "far"}}})");
  auto r = test::run("XDG_CONFIG_HOME=" + dir_.path() + " " + test::bin("foveal") + " profile show b");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("gaze_quality.left: accuracy_deg: expected a number"), std::string::npos) << r.err;
  test::write_file(dir_.path("foveal/profiles/b.json"), R"({"gaze_quality": {"middle": {}}})");
  r = test::run("XDG_CONFIG_HOME=" + dir_.path() + " " + test::bin("foveal") + " profile show b");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("gaze_quality: unknown key 'middle'"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace foveal

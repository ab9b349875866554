// `foveal calibrate --answers` end to end: scripts in, profiles out.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>

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

}  // namespace
}  // namespace foveal

// foveal devices --display-model: a Vive configuration (saved, or read from a headset
// in the VM test) written as a display-model file that foveal loads back with the
// configuration's values; bad input exits 2 and writes nothing.
#include <gtest/gtest.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "foveal/core/display_model.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

TEST(DisplayModelCli, WritesTheConfigurationsModel) {
  test::TempDir dir;
  const std::string out = dir.path("vive.json");
  auto r = test::run(test::bin("foveal") + " devices --from-config " +
                     test::source_path("data/headset/vive_pro_config_example.json") + " --display-model " + out + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["display_model"], out);
  auto m = DisplayModel::load(out);
  ASSERT_TRUE(m) << m.error().message;
  EXPECT_EQ(m->name, "vive_vive_pro_mv");
  EXPECT_EQ(m->eye_width, 1440);
  EXPECT_EQ(m->eye_height, 1600);
  EXPECT_FLOAT_EQ(m->ipd_mm, 63.5f);
  EXPECT_TRUE(m->distortion[0].enabled && m->distortion[1].enabled);
  const auto file = nlohmann::json::parse(test::read_file(out));
  EXPECT_NE(file["source"].get<std::string>().find("rms"), std::string::npos);
}

TEST(DisplayModelCli, BadConfigurationExitsTwoAndWritesNothing) {
  test::TempDir dir;
  const std::string cfg = dir.path("bad.json"), out = dir.path("vive.json");
  test::write_file(cfg, "{\"model_number\": \"Vive MV\", \"device\": {\"eye_target_width_in_pixels\": 1080}}");
  auto r = test::run(test::bin("foveal") + " devices --from-config " + cfg + " --display-model " + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("eye_target_height_in_pixels: missing"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  auto alone = test::run(test::bin("foveal") + " devices --from-config " + cfg);
  EXPECT_EQ(alone.exit_code, 2);
}

}  // namespace
}  // namespace foveal

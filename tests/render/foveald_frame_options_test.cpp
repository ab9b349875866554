// foveald's frame options as a user runs them: --temporal on in both outputs it has on
// a machine without a headset (headless through EGL, a GLFW window on a real X server),
// and --blend-at samples. What each frame did is read back from summary.json: the
// accumulation's histories exist only once it has run, and the layers composited at the
// kept samples are counted per frame.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "khronos_models.hpp"
#include "test_support.hpp"

using namespace foveal;

namespace {

// foveald for 3 frames of `scene` with `args`, headless or in a window under Xvfb; the
// summary's render object.
nlohmann::json run_foveald(test::TempDir& d, const std::string& scene, const std::string& args, bool window) {
  const std::string foveald = test::bin("foveald") + (window ? " --window" : " --headless") + " --frames 3 --size 320x180 --scene " +
                              scene + " --no-control --no-shm -q " + args + " --out " + d.path("out");
  const std::string cmd = "XDG_CONFIG_HOME=" + d.path() + " XDG_STATE_HOME=" + d.path("state") + " " +
                          (window ? "xvfb-run -a -s '-screen 0 1280x720x24' " + foveald : foveald);
  auto r = test::run(cmd);
  EXPECT_EQ(r.exit_code, 0) << cmd << "\n" << r.err;
  if (r.exit_code != 0) return {};
  const auto j = nlohmann::json::parse(test::read_file(d.path("out/summary.json")));
  EXPECT_EQ(j["render"]["frames"].get<int>(), 3) << j["render"].dump();
  return j["render"];
}

}  // namespace

TEST(FovealdFrameOptions, TemporalOnAccumulatesHeadlessAndInAWindow) {
  ASSERT_TRUE(std::filesystem::exists("/usr/bin/xvfb-run")) << "install xvfb and xauth (scripts/bootstrap.sh does)";
  for (bool window : {false, true}) {
    const char* where = window ? "window" : "headless";
    test::TempDir on_dir, off_dir;
    const auto on = run_foveald(on_dir, "pattern:checker", "--temporal on", window);
    const auto off = run_foveald(off_dir, "pattern:checker", "--temporal off", window);
    ASSERT_TRUE(on.is_object() && off.is_object()) << where;
    EXPECT_EQ(on["output"]["kind"], where);
    EXPECT_EQ(on["temporal"], "on") << where;
    EXPECT_GT(on["temporal_history_mb"].get<double>(), 0.0) << where << ": no history: the frames did not accumulate";
    EXPECT_EQ(off["temporal"], "off") << where;
    EXPECT_EQ(off["temporal_history_mb"].get<double>(), 0.0) << where;
  }
}

TEST(FovealdFrameOptions, BlendAtSamplesCompositesTheBlendedSurfacesInTheReducedBuffer) {
  const std::string scene = test::khronos("AlphaBlendModeTest");
  test::TempDir samples_dir, output_dir;
  const auto samples = run_foveald(samples_dir, scene, "--blend-at samples", false);
  const auto output = run_foveald(output_dir, scene, "", false);
  ASSERT_TRUE(samples.is_object() && output.is_object());
  EXPECT_EQ(samples["blend_at"], "samples");
  EXPECT_GT(samples["blend_layers_last_frame"].get<int>(), 0) << "no layer was composited at the kept samples";
  EXPECT_EQ(output["blend_at"], "output") << "the default";
  EXPECT_EQ(output["blend_layers_last_frame"].get<int>(), 0);
}

TEST(FovealdFrameOptions, BlendAtSamplesWithTheGbufferPipelineIsRefused) {
  test::TempDir d;
  auto r = test::run("XDG_CONFIG_HOME=" + d.path() + " " + test::bin("foveald") +
                     " --headless --frames 1 --size 320x180 --scene pattern:checker --no-control --no-shm -q"
                     " --pipeline gbuffer --blend-at samples --out " + d.path("out"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--blend-at samples needs --pipeline visibility"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(d.path("out/summary.json"))) << "refused before any output";
}

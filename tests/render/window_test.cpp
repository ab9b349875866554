// The GLFW window paths on a real (virtual) X server: foveald --window renders frames,
// and `foveal calibrate`'s in-headset mode takes its answers from real key presses.
// Xvfb, xauth and xdotool come from scripts/bootstrap.sh; without them these tests fail.
#include <gtest/gtest.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "test_support.hpp"

using namespace foveal;

namespace {
bool have_x_tools() {
  for (const char* tool : {"/usr/bin/xvfb-run", "/usr/bin/xdotool"})
    if (!std::filesystem::exists(tool)) {
      ADD_FAILURE() << tool << " is missing: install xvfb, xauth and xdotool (scripts/bootstrap.sh does)";
      return false;
    }
  return true;
}
}  // namespace

TEST(Window, FovealdRendersIntoAWindow) {
  ASSERT_TRUE(have_x_tools());
  test::TempDir d;
  auto r = test::run("XDG_CONFIG_HOME=" + d.path() + " xvfb-run -a -s '-screen 0 1280x720x24' " + test::bin("foveald") +
                     " --window --frames 3 --size 480x270 --scene pattern:checker --no-control --no-shm -q --out " + d.path("out"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(test::read_file(d.path("out/summary.json")));
  EXPECT_EQ(j["render"]["frames"].get<int>(), 3);
  // Pacing stats: every frame presented. Missed refreshes need the monitor's rate, which
  // Xvfb does not report (0): then "unknown", never a made-up count.
  const auto& out = j["render"]["output"];
  EXPECT_EQ(out["kind"], "window");
  EXPECT_EQ(out["present"]["presented"].get<int>(), 3);
  if (out["present"]["refresh_hz"].get<double>() > 0) EXPECT_TRUE(out["present"]["missed"].is_number()) << out.dump();
  else EXPECT_TRUE(out["present"]["missed"].is_null()) << out.dump();
  EXPECT_TRUE(out["present"].contains("interval_ms")) << out.dump();
}

TEST(Window, CalibrationTakesAnswersFromTheKeyboard) {
  ASSERT_TRUE(have_x_tools());
  test::TempDir d;
  // Left-dominant Miles answers, then the slider and validation: the same answers as the
  // scripted test "l l l same different s s s". The inner script's $ are escaped so that
  // the inner shell, inside the X server, expands them (not the outer one).
  const std::string script =
      test::bin("foveal") + " calibrate --profile w --scene pattern:checker --json > " + d.path("out.json") + " 2> " +
      d.path("err.txt") + " & P=\\$!; " +
      "W=\\$(xdotool search --sync --onlyvisible --name 'foveal calibrate' | head -1); xdotool windowfocus --sync \\$W; "
      "xdotool key --delay 150 l l l s d s s s; wait \\$P";
  auto r = test::run("XDG_CONFIG_HOME=" + d.path() + " timeout 120 xvfb-run -a -s '-screen 0 1280x720x24' sh -c \"" + script + "\"");
  ASSERT_EQ(r.exit_code, 0) << r.err << test::read_file(d.path("err.txt"));
  const auto out = nlohmann::json::parse(test::read_file(d.path("out.json")));
  EXPECT_EQ(out["dominant_eye"], "left");
  EXPECT_EQ(out["saved"], true);
  // Each step is told in the terminal too (and drawn into the picture); the 2880x1600
  // frames do not fit Xvfb's 1280x720 screen, so they are shrunk, warned about, and the
  // result says what the answers were judged on.
  const std::string err = test::read_file(d.path("err.txt"));
  for (const char* step : {"foveal calibrate: dominant_eye, trial 1: ", "foveal calibrate: dominant_eye, trial 3: ",
                           "foveal calibrate: sigma_uniform, trial 1: ", "foveal calibrate: validation, trial 1: "})
    EXPECT_NE(err.find(step), std::string::npos) << step << " not in:\n" << err;
  EXPECT_NE(err.find("warning: the 2880x1600 frames are shown at 1280x711"), std::string::npos) << err;
  EXPECT_EQ(out["judged_on"]["frames"], nlohmann::json({2880, 1600}));
  EXPECT_EQ(out["judged_on"]["shown"], nlohmann::json({1280, 711}));
  EXPECT_NEAR(out["judged_on"]["scale"].get<double>(), 1280.0 / 2880.0, 1e-3);
  EXPECT_TRUE(out["judged_on"]["monitor"].is_null());
  const auto profile = nlohmann::json::parse(test::read_file(d.path("foveal/profiles/w.json")));
  EXPECT_EQ(profile["dominant_eye"], "left");
}

TEST(Window, NoDisplayIsAClearError) {
  test::TempDir d;
  auto r = test::run("env -u DISPLAY -u WAYLAND_DISPLAY XDG_CONFIG_HOME=" + d.path() + " " + test::bin("foveal") + " calibrate --dry-run");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("--answers"), std::string::npos) << r.err;
}

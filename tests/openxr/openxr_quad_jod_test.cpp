// Issue 37 item 5(c): the stereo image the layer composes from an app's quad views, read
// back and scored against a full-density stereo render of the same frame, holds the JOD
// the inset levels table predicts at the true gaze.
//
// The runtime here is Monado's simulated HMD on the null compositor: 320x240 per eye over
// 85 x 89 degrees (3.8 ppd), nothing like a headset, so the table is that display's own:
// tests/openxr/data/monado_null_simulated.json and its .inset-levels.json, built by
// `foveal bench --methods inset` on the Dungeon (docs/openxr.md, "How the quad views are
// tested"). The app renders the Dungeon with its own shader from the runtime's view, the
// table's frames come from foveal's compositor from the scene's camera: the same content,
// not the same pixels.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "foveal/core/display_model.hpp"
#include "foveal/core/gaze_log.hpp"
#include "foveal/image/image.hpp"
#include "foveal/perception/jod.hpp"
#include "foveal/runtime/inset_levels.hpp"
#include "quad_views_fixture.hpp"

namespace foveal {
namespace {

using nlohmann::json;
using test::QuadViews;
using test::Tan;
using test::tangents;

// The table is a mean over 7 frames of the reference set, whose JOD spread over frames is
// under 0.1 at a level; the app's view of the Dungeon is another frame of the same scene.
constexpr double kTolerance = 0.3;
// Where both eyes look, in the head's frame: 10 degrees right, 5 up (off the optical
// centre, so a fixed inset would not be at the gaze).
constexpr double kTanX = 0.17632698, kTanY = 0.08748866;  // tan(10°), tan(5°)

TEST_F(QuadViews, TheComposedImageHoldsTheJodTheInsetTableDisplayPredictsAtTheTrueGaze) {
  const std::string model_path = test::source_path("tests/openxr/data/monado_null_simulated.json");
  auto model = DisplayModel::load(model_path);
  ASSERT_TRUE(model) << model.error().message;
  // What the layer will choose: the default profile's EFR ratio (σ 2 and 3), the right eye dominant.
  const std::string quality = "jod:8.7";
  auto chosen = inset_quality(quality, model_path, 1.5);
  ASSERT_TRUE(chosen && chosen->has_value()) << (chosen ? "no levels" : chosen.error().message);
  const InsetLevels& levels = **chosen;
  ASSERT_GT(levels.sigma_d, 1.1) << "the table foveates at this target";

  ASSERT_NO_FATAL_FAILURE(test::write_fixation_log(rig_.path("fixation.csv"), 6, kTanX, kTanY));
  auto fd = rig_.foveald({"--source", "replay:" + rig_.path("fixation.csv"), "--end", "5", "--loop", "--no-render", "--out",
                          rig_.path("fd")},
                         "foveald");
  wait_for_block();
  std::filesystem::create_directories(rig_.path("capture"));
  std::filesystem::create_directories(rig_.path("full"));
  // Frame 40: the inset's ease from the fixed place (150 ms of display time) is long over.
  constexpr int kFrame = 40;
  const auto quad = run_app({"--frames", std::to_string(kFrame + 2)}, "quad",
                            {"FOVEAL_OPENXR_CAPTURE_DIR=" + rig_.path("capture"),
                             "FOVEAL_OPENXR_CAPTURE_FRAME=" + std::to_string(kFrame), "FOVEAL_OPENXR_QUALITY=" + quality,
                             "FOVEAL_OPENXR_DISPLAY=" + model_path});
  fd->signal(SIGTERM);
  ASSERT_EQ(fd->wait(30000), 0) << rig_.err("foveald");
  run_app({"--frames", "3", "--stereo", "--save-frame", "2", "--save-dir", rig_.path("full")}, "full", {"FOVEAL_OPENXR_DISABLE=1"});

  const auto fs = frames(quad);
  ASSERT_GT(fs.size(), static_cast<std::size_t>(kFrame)) << rig_.err("quad");
  const json& f = fs[kFrame];
  auto composed = image::load(rig_.path("capture/composed.png"));
  ASSERT_TRUE(composed) << composed.error().message << "\n" << rig_.err("quad");
  auto l = image::load(rig_.path("full/view_0.png")), r = image::load(rig_.path("full/view_1.png"));
  ASSERT_TRUE(l && r) << rig_.err("full");
  const int w = l->width, h = l->height;
  ASSERT_EQ(w, model->eye_width) << "the runtime's recommended size is the test display's";
  ASSERT_EQ(h, model->eye_height);
  ASSERT_EQ(composed->width, 2 * w);
  ASSERT_EQ(composed->height, h);

  const double sigma[2] = {levels.sigma_nd, levels.sigma_d}, predicted[2] = {levels.jod_nd, levels.jod_d};
  int scored = 0;
  for (int e = 0; e < 2; ++e) {
    // The captured frame's inner view is on the gaze: the inset was tracking, not eased.
    const Tan o = tangents(f["views"][e]), i = tangents(f["views"][e + 2]);
    const double off_deg = std::atan(std::hypot(i.cx() - kTanX, i.cy() - kTanY)) * 180 / M_PI;
    ASSERT_LT(off_deg, 0.5) << "eye " << e << ": frame " << kFrame << "'s inner view is not on the gaze: " << f.dump();
    // The true gaze in the eye's image (top row first).
    const perception::Fixation at{(kTanX - o.l) / (o.r - o.l) * w, (o.u - kTanY) / (o.u - o.d) * h};
    const perception::JodMetric metric(perception::eye_geometry(*model, e == 0 ? Eye::left : Eye::right, w, h), {});
    auto score = metric.still(e == 0 ? *l : *r, image::crop(*composed, {e * w, 0, w, h}), at);
    ASSERT_TRUE(score) << score.error().message;
    std::printf("eye %d: sigma %.3f, extent %.1f deg: JOD %.3f at the true gaze (%.1f, %.1f px), predicted %.3f\n", e, sigma[e],
                levels.extent_deg, score->jod, at.x, at.y, predicted[e]);
    if (std::isnan(predicted[e])) continue;  // σ_nd past the table's grid: nothing predicted
    ++scored;
    EXPECT_NEAR(score->jod, predicted[e], kTolerance) << "eye " << e << ", sigma " << sigma[e];
  }
  EXPECT_GE(scored, 1) << "no eye had a prediction";
}

}  // namespace
}  // namespace foveal

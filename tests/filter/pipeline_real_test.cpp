// The pipeline on the three real Vive Pro Eye recordings (no ground truth: behaviour).
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "foveal/core/gaze_log.hpp"
#include "foveal/import/importers.hpp"
#include "foveal/runtime/gaze_pipeline.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

class PipelineOnVive : public ::testing::TestWithParam<const char*> {
 protected:
  std::vector<GazeSample> load() {
    const std::string out = dir_.path("log.csv");
    auto imp = import_sranipal(test::source_path(std::string("data/gaze/vive_pro_eye/") + GetParam() + ".csv"), out);
    EXPECT_TRUE(imp) << imp.error().message;
    auto samples = read_gaze_log(out);
    EXPECT_TRUE(samples) << samples.error().message;
    return samples ? *samples : std::vector<GazeSample>{};
  }
  test::TempDir dir_;
};

TEST_P(PipelineOnVive, NoNanNoJumpsToCornersOrTheOriginInBlinks) {
  const auto samples = load();
  ASSERT_FALSE(samples.empty());
  const DisplayModel m = DisplayModel::vive_pro_eye();
  GazePipeline pipe(m, FilterConfig{});
  glm::vec2 last_good[2] = {{720, 800}, {720, 800}};
  int blink_samples = 0;
  for (const GazeSample& s : samples) {
    const FoveaFrame f = pipe.update(s);
    for (int e = 0; e < 2; ++e) {
      const FoveaPoint& p = f.eyes[e];
      ASSERT_TRUE(std::isfinite(p.px.x) && std::isfinite(p.px.y));
      ASSERT_GE(p.px.x, 0.0f);
      ASSERT_LT(p.px.x, 1440.0f);
      ASSERT_GE(p.px.y, 0.0f);
      ASSERT_LT(p.px.y, 1600.0f);
      if (p.state == FoveaState::blink) {
        ++blink_samples;
        // Held: exactly where the eye last looked, never a corner or the origin.
        EXPECT_FLOAT_EQ(p.px.x, last_good[e].x);
        EXPECT_FLOAT_EQ(p.px.y, last_good[e].y);
        EXPECT_GT(std::hypot(p.px.x, p.px.y), 50.0f);
      } else if (p.state != FoveaState::lost) {
        last_good[e] = p.px;
      }
    }
  }
  EXPECT_GT(blink_samples, 0) << "every recording has blinks";
}

INSTANTIATE_TEST_SUITE_P(Recordings, PipelineOnVive,
                         ::testing::Values("TESTNA01_2D_Fist3", "TESTNA05_360VR_Spread7", "TESTNA15_2D_Pen3"));

TEST(PipelineOnViveEnd, TheLongLossAtTheEndOfTestna01EndsAtTheCentre) {
  test::TempDir dir;
  ASSERT_TRUE(import_sranipal(test::source_path("data/gaze/vive_pro_eye/TESTNA01_2D_Fist3.csv"), dir.path("l.csv")));
  auto samples = read_gaze_log(dir.path("l.csv"));
  ASSERT_TRUE(samples);
  const DisplayModel m = DisplayModel::vive_pro_eye();
  FilterConfig cfg;
  GazePipeline pipe(m, cfg);
  FoveaFrame f;
  for (const GazeSample& s : *samples) f = pipe.update(s);
  // The documented fallback after hold_ms with both eyes gone: the viewport centre, lost.
  for (int e = 0; e < 2; ++e) {
    EXPECT_EQ(f.eyes[e].state, FoveaState::lost);
    EXPECT_FLOAT_EQ(f.eyes[e].confidence, 0.0f);
    EXPECT_NEAR(f.eyes[e].px.x, 720.0f, 1.0f);
    EXPECT_NEAR(f.eyes[e].px.y, 800.0f, 1.0f);
  }
}

TEST(PipelineFallbacks, OneEyeMissingUsesTheOtherAfterTheHold) {
  FilterConfig cfg;
  cfg.hold_ms = 50;
  GazePipeline pipe(DisplayModel::vive_pro_eye(), cfg);
  GazeSample s;
  for (int i = 0; i < 60; ++i) {
    s.t_ns = static_cast<TimeNs>(i) * 8'333'333;
    for (int e = 0; e < 2; ++e) {
      s.eyes[e].valid = kValidDirection;
      // Converging on a near target: the left eye looks right of the right eye's gaze.
      s.eyes[e].direction = glm::normalize(glm::vec3(e == 0 ? 0.05f : -0.05f, 0.0f, -1.0f));
    }
    if (i >= 30) s.eyes[0].valid = 0;  // the left eye drops out
    const FoveaFrame f = pipe.update(s);
    if (i >= 30 && i < 36) {
      EXPECT_EQ(f.eyes[0].state, FoveaState::blink) << i;  // held within 50 ms
    }
    if (i >= 38) {
      EXPECT_EQ(f.eyes[0].state, FoveaState::fixation) << i;  // from the right eye ...
      EXPECT_NEAR(f.eyes[0].px.x, pipe.model().direction_to_pixel(Eye::left, s.eyes[1].direction).x + 2 * 0.05f * 753.6f, 3.0f)
          << "... corrected for vergence";
      EXPECT_FLOAT_EQ(f.eyes[0].confidence, 0.5f);
    }
  }
}

TEST(PipelineValidation, NanZeroNonUnitClosedAndOffscreenAreInvalid) {
  GazePipeline pipe(DisplayModel::vive_pro_eye(), FilterConfig{});
  const glm::vec3 bad[] = {{NAN, 0, -1}, {0, 0, 0}, {0, 0, -2}, {0, 0, 1}, {0.99f, 0.0f, -0.14f}};
  for (const glm::vec3& d : bad) {
    GazeSample s;
    s.eyes[0].valid = kValidDirection;
    s.eyes[0].direction = d;
    pipe.update(s);
    EXPECT_FALSE(pipe.events(Eye::left).valid) << d.x << "," << d.y << "," << d.z;
  }
  GazeSample closed;
  closed.eyes[0].valid = kValidDirection | kValidOpenness;
  closed.eyes[0].direction = {0, 0, -1};
  closed.eyes[0].openness = 0.02f;
  pipe.update(closed);
  EXPECT_FALSE(pipe.events(Eye::left).valid);
}

}  // namespace
}  // namespace foveal

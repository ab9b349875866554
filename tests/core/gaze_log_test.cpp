#include <gtest/gtest.h>

#include <cmath>

#include "foveal/core/gaze_log.hpp"
#include "test_support.hpp"

namespace foveal {

TEST(GazeLog, RoundTripIsBitExact) {
  test::TempDir dir;
  GazeLogHeader h;
  h.rate_hz = 120;
  std::vector<GazeSample> in(3);
  for (std::size_t i = 0; i < in.size(); ++i) {
    in[i].t_ns = static_cast<TimeNs>(i) * 8'333'333 + 17;
    in[i].eyes[0].valid = kValidAll;
    in[i].eyes[0].direction = {0.1234567f + static_cast<float>(i), -1e-7f, -0.99f};
    in[i].eyes[0].pupil_mm = 3.14159274f;
    in[i].eyes[0].openness = 1.0f / 3.0f;
  }
  auto w = GazeLogWriter::create(dir.path("a.csv"), h);
  ASSERT_TRUE(w) << w.error().message;
  for (const auto& s : in) ASSERT_TRUE(w->write(s));
  ASSERT_TRUE(w->commit());
  auto out = read_gaze_log(dir.path("a.csv"));
  ASSERT_TRUE(out) << out.error().message;
  EXPECT_EQ(*out, in);
}

TEST(GazeLog, V2RoundTripIsBitExactWithAndWithoutAPose) {
  test::TempDir dir;
  GazeLogHeader h;
  h.version = kGazeLogV2;
  h.rate_hz = 120;
  std::vector<GazeSample> in(4);
  for (std::size_t i = 0; i < in.size(); ++i) {
    in[i].t_ns = static_cast<TimeNs>(i) * 8'333'333;
    in[i].eyes[1].valid = kValidDirection;
    in[i].eyes[1].direction = {0.0f, 0.0f, -1.0f};
    if (i == 2) continue;  // no pose in this row
    in[i].head.valid = true;
    in[i].head.pose.position_m = {0.9747f + static_cast<float>(i) * 1e-7f, 1.178f, -0.5525f};
    in[i].head.pose.orientation = glm::normalize(glm::quat(0.99f, -0.0413f, 0.0289f, 1.0f / 3.0f));
  }
  in[3].head.pose.orientation = -in[3].head.pose.orientation;  // w < 0 is kept as written
  auto w = GazeLogWriter::create(dir.path("a.csv"), h);
  ASSERT_TRUE(w) << w.error().message;
  for (const auto& s : in) ASSERT_TRUE(w->write(s));
  ASSERT_TRUE(w->commit());
  const std::string text = test::read_file(dir.path("a.csv"));
  EXPECT_EQ(text.rfind("# foveal-gaze-log v2\n", 0), 0u);
  EXPECT_NE(text.find(",head_valid,head_x_m,head_y_m,head_z_m,head_qw,head_qx,head_qy,head_qz\n"), std::string::npos);
  EXPECT_NE(text.find(",0,,,,,,,\n"), std::string::npos) << "the row without a pose has empty head fields";
  GazeLogHeader back;
  auto out = read_gaze_log(dir.path("a.csv"), &back);
  ASSERT_TRUE(out) << out.error().message;
  EXPECT_EQ(back.version, kGazeLogV2);
  EXPECT_EQ(*out, in);
  EXPECT_FALSE((*out)[2].head.valid);
}

TEST(GazeLog, V1LogsStillReadWithoutAPose) {
  auto log = read_gaze_log(test::source_path("tests/vm/data/constant_gaze.csv"));
  ASSERT_TRUE(log) << log.error().message;
  ASSERT_FALSE(log->empty());
  for (const GazeSample& s : *log) EXPECT_FALSE(s.head.valid);
}

TEST(GazeLog, V1WriterRefusesAPoseRatherThanDroppingIt) {
  test::TempDir dir;
  GazeLogHeader h;
  h.rate_hz = 120;
  auto w = GazeLogWriter::create(dir.path("a.csv"), h);
  ASSERT_TRUE(w) << w.error().message;
  GazeSample s;
  s.head.valid = true;
  auto st = w->write(s);
  ASSERT_FALSE(st);
  EXPECT_NE(st.error().message.find("head"), std::string::npos) << st.error().message;
}

TEST(GazeLog, V2WriterRefusesANonUnitOrNonFiniteHeadPose) {
  test::TempDir dir;
  GazeLogHeader h;
  h.version = kGazeLogV2;
  h.rate_hz = 120;
  auto w = GazeLogWriter::create(dir.path("a.csv"), h);
  ASSERT_TRUE(w) << w.error().message;
  GazeSample s;
  s.head.valid = true;
  s.head.pose.orientation = glm::quat(0.5f, 0, 0, 0);
  EXPECT_FALSE(w->write(s));
  s.head.pose.orientation = glm::quat(1, 0, 0, 0);
  s.head.pose.position_m.z = std::nanf("");
  EXPECT_FALSE(w->write(s));
  h.version = 3;
  EXPECT_FALSE(GazeLogWriter::create(dir.path("b.csv"), h));
}

}  // namespace foveal

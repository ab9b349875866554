#include <gtest/gtest.h>

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

}  // namespace foveal

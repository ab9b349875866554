#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "foveal/drivers/hid/device_clock.hpp"
#include "foveal/drivers/hid/screen_gaze.hpp"

namespace foveal::hid {
namespace {

TEST(HidScreenGaze, EyesLookFromTheirPositionsToTheGazePoint) {
  TrackingData t;
  t.gaze_valid = true;
  t.gaze_x_mm = 300;  // screen centre of a 600 x 340 mm plane
  t.gaze_y_mm = 170;
  t.left_valid = t.right_valid = true;
  t.left_eye_mm = {268, 170, 600};
  t.right_eye_mm = {332, 170, 600};
  ScreenPlane p;
  p.width_mm = 600;
  p.height_mm = 340;
  const GazeSample s = screen_gaze_to_sample(t, p);
  ASSERT_EQ(s.eyes[0].valid, kValidDirection | kValidOrigin);
  ASSERT_EQ(s.eyes[1].valid, kValidDirection | kValidOrigin);
  // Both eyes converge on the point: the left eye looks right, the right eye left, both forward (-z).
  EXPECT_GT(s.eyes[0].direction.x, 0);
  EXPECT_LT(s.eyes[1].direction.x, 0);
  EXPECT_NEAR(s.eyes[0].direction.x, 32 / std::hypot(32.0, 600.0), 1e-6);
  EXPECT_NEAR(s.eyes[0].direction.z, -600 / std::hypot(32.0, 600.0), 1e-6);
  EXPECT_NEAR(s.eyes[0].direction.y, 0, 1e-7);
  // Origins in the head frame: left eye at x < 0, IPD apart.
  EXPECT_FLOAT_EQ(s.eyes[0].origin_mm.x, -32);
  EXPECT_FLOAT_EQ(s.eyes[1].origin_mm.x, 32);
  EXPECT_FLOAT_EQ(s.combined.direction.z, -1);
}

TEST(HidScreenGaze, ScreenYDownIsHeadYUpAndNominalEyesWithoutPositions) {
  TrackingData t;
  t.gaze_valid = true;
  t.gaze_x_mm = 300;
  t.gaze_y_mm = 0;  // top edge
  ScreenPlane p;
  p.width_mm = 600;
  p.height_mm = 340;
  p.viewing_distance_mm = 650;
  const GazeSample s = screen_gaze_to_sample(t, p);
  EXPECT_EQ(s.eyes[0].valid, kValidDirection);  // nominal eyes: no origin
  EXPECT_GT(s.eyes[0].direction.y, 0);           // looking up
  EXPECT_NEAR(s.combined.direction.y, 170 / std::hypot(170.0, 650.0), 1e-6);
  EXPECT_NEAR(glm::length(s.eyes[1].direction), 1.0f, 1e-6f);
}

TEST(HidScreenGaze, NoGazePointNoValidBits) {
  TrackingData t;
  const GazeSample s = screen_gaze_to_sample(t, ScreenPlane{});
  EXPECT_EQ(s.eyes[0].valid, 0u);
  EXPECT_EQ(s.eyes[1].valid, 0u);
  EXPECT_EQ(s.combined.valid, 0u);
}

TEST(HidDeviceClock, BurstKeepsDeviceSpacingAndTimesIncrease) {
  DeviceClock c;
  const TimeNs base = 1'000'000'000;
  EXPECT_EQ(c.map(base + 2'000'000, 0), base + 2'000'000);
  // Three reports 8.33 ms apart on the device, read in one burst.
  const TimeNs t1 = c.map(base + 30'000'000, 8'333'000);
  const TimeNs t2 = c.map(base + 30'000'100, 16'666'000);
  EXPECT_EQ(t1, base + 2'000'000 + 8'333'000);
  EXPECT_EQ(t2 - t1, 8'333'000);
  // A less-delayed report tightens the offset.
  EXPECT_EQ(c.map(base + 25'000'500, 25'000'000), base + 25'000'500);
  // Device clock restarts (replug): re-anchored on arrival.
  EXPECT_EQ(c.map(base + 40'000'000, 5), base + 40'000'000);
  // No device time: arrival, but never backwards.
  EXPECT_EQ(c.map(base + 39'000'000, std::nullopt), base + 40'000'001);
  // Garbage device time does not overflow.
  const TimeNs g = c.map(base + 50'000'000, std::numeric_limits<std::int64_t>::max());
  EXPECT_EQ(g, base + 50'000'000);
}

TEST(HidDeviceClock, SlowDeviceClockFollowsArrivals) {
  DeviceClock c;
  c.map(1'000'000'000, 0);
  // The device says 10 ms passed, the host saw 100 ms: more than kMaxLagNs behind.
  EXPECT_EQ(c.map(1'100'000'000, 10'000'000), 1'100'000'000);
}

}  // namespace
}  // namespace foveal::hid

// The camera paths of `foveal bench --flicker` (tools/bench/src/camera_path.cpp) without
// rendering: specs and their refusals, the back-and-forth wave, the orbit keeping its
// pivot ahead at a constant distance, the dolly along the line of sight, the defaults
// from a scene's bounds.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "foveal/bench/camera_path.hpp"

using namespace foveal;
using namespace foveal::bench;

namespace {

// Where the head-frame point p lands under the relative pose.
glm::vec3 apply(const Pose& pose, glm::vec3 p) { return pose.orientation * p + pose.position_m; }

TEST(CameraPath, SpecsParseAndPrintBack) {
  for (const char* spec : {"static", "recorded", "orbit", "dolly", "orbit:45", "dolly:0.5"}) {
    auto p = parse_camera_path(spec);
    ASSERT_TRUE(p) << spec << ": " << p.error().message;
    EXPECT_EQ(p->text(), spec);
  }
  EXPECT_EQ(parse_camera_path("orbit:12.5")->speed, 12.5);
  EXPECT_EQ(parse_camera_path("orbit")->speed, 0.0);  // not given: with_default_speed sets it
  EXPECT_EQ(with_default_speed(*parse_camera_path("orbit"), 3.0).speed, kDefaultOrbitDegPerS);
  EXPECT_DOUBLE_EQ(with_default_speed(*parse_camera_path("dolly"), 3.0).speed, kDefaultDollyPivotsPerS * 3.0);
  EXPECT_EQ(with_default_speed(*parse_camera_path("dolly:2"), 3.0).speed, 2.0);  // a given speed stays
}

TEST(CameraPath, BadSpecsNameTheOptionAndTheSpec) {
  for (const char* spec : {"spin", "", "orbit:", "orbit:-1", "orbit:0", "dolly:fast", "orbit:nan", "static:3", "recorded:1", "Orbit"}) {
    auto p = parse_camera_path(spec, "--camera-path");
    ASSERT_FALSE(p) << spec;
    EXPECT_EQ(p.error().kind, ErrorKind::bad_input);
    EXPECT_NE(p.error().message.find(std::string("--camera-path: '") + spec + "'"), std::string::npos) << p.error().message;
  }
}

TEST(CameraPath, BackAndForthRisesFirstTurnsAtTheEndsAndRepeats) {
  EXPECT_EQ(back_and_forth(0, -2, 2), 0);
  EXPECT_DOUBLE_EQ(back_and_forth(1.5, -2, 2), 1.5);
  EXPECT_DOUBLE_EQ(back_and_forth(2, -2, 2), 2);
  EXPECT_DOUBLE_EQ(back_and_forth(3, -2, 2), 1);   // turned at hi
  EXPECT_DOUBLE_EQ(back_and_forth(6, -2, 2), -2);  // the other end
  EXPECT_DOUBLE_EQ(back_and_forth(7, -2, 2), -1);
  EXPECT_NEAR(back_and_forth(8, -2, 2), 0, 1e-12);  // one period: 2 * (hi - lo)
  EXPECT_NEAR(back_and_forth(8 + 1.25, -2, 2), back_and_forth(1.25, -2, 2), 1e-12);
  EXPECT_DOUBLE_EQ(back_and_forth(1.5, 0, 1), 0.5);  // lo = 0: a dolly's
  // Continuous, bounded, and moving at speed 1 everywhere.
  for (double s = 0; s < 30; s += 0.01) {
    const double a = back_and_forth(s, -2, 2), b = back_and_forth(s + 0.01, -2, 2);
    EXPECT_GE(a, -2 - 1e-12);
    EXPECT_LE(a, 2 + 1e-12);
    EXPECT_LE(std::abs(b - a), 0.01 + 1e-9) << s;
  }
}

TEST(CameraPath, StaticRecordedAndTimeZeroAreTheSceneViewExactly) {
  for (const char* spec : {"static", "recorded", "orbit:30", "dolly:1"}) {
    const CameraPath p = *parse_camera_path(spec);
    EXPECT_EQ(camera_pose(p, 2.0, 0.0), Pose{}) << spec;
  }
  EXPECT_EQ(camera_pose(*parse_camera_path("static"), 2.0, 1.7), Pose{});
}

TEST(CameraPath, OrbitKeepsThePivotAheadAtItsDistance) {
  const double pivot = 2.5;
  const CameraPath orbit = *parse_camera_path("orbit:30");
  const glm::vec3 pivot_point(0, 0, -pivot);  // in the start view's head frame
  double max_deg = 0;
  for (double t = 0.05; t < 3; t += 0.05) {
    const Pose p = camera_pose(orbit, pivot, t);
    EXPECT_NEAR(glm::length(p.position_m - pivot_point), pivot, 1e-5) << t;       // on the circle
    EXPECT_NEAR(glm::length(apply(p, glm::vec3(0, 0, -pivot)) - pivot_point), 0, 1e-5) << t;  // facing the pivot
    EXPECT_NEAR(p.position_m.y, 0, 1e-7);                                          // about the up axis
    const double deg = glm::degrees(glm::angle(p.orientation));
    max_deg = std::max(max_deg, deg);
    EXPECT_LE(deg, kOrbitHalfRangeDeg + 1e-3);
  }
  EXPECT_NEAR(max_deg, kOrbitHalfRangeDeg, 1.6);  // reaches its ends (samples every 1.5 degrees)
  // 30 deg/s: a quarter second turns 7.5 degrees, to the right of the start (+x).
  const Pose q = camera_pose(orbit, pivot, 0.25);
  EXPECT_NEAR(glm::degrees(glm::angle(q.orientation)), 7.5, 1e-3);
  EXPECT_GT(q.position_m.x, 0);
}

TEST(CameraPath, DollyMovesAlongTheLineOfSightAndBack) {
  const double pivot = 4.0;
  const CameraPath dolly = *parse_camera_path("dolly:1");
  const Pose a = camera_pose(dolly, pivot, 0.5);
  EXPECT_EQ(a.orientation, glm::quat(1, 0, 0, 0));
  EXPECT_FLOAT_EQ(a.position_m.z, -0.5f);  // forward is -z
  EXPECT_EQ(a.position_m.x, 0.0f);
  EXPECT_FLOAT_EQ(camera_pose(dolly, pivot, 2.0).position_m.z, static_cast<float>(-kDollyReach * pivot));  // the far end
  EXPECT_FLOAT_EQ(camera_pose(dolly, pivot, 3.0).position_m.z, -1.0f);  // on its way back
  for (double t = 0; t < 10; t += 0.1) {
    const float z = camera_pose(dolly, pivot, t).position_m.z;
    EXPECT_LE(z, 1e-6f);
    EXPECT_GE(z, -kDollyReach * pivot - 1e-5);  // never reaches the pivot
  }
}

TEST(CameraPath, DefaultsFollowTheSceneBounds) {
  // A view at (0, 0, 10) looking down -z at a sphere of radius 2 about the origin.
  glm::mat4 view(1.0f);
  view[3] = glm::vec4(0, 0, 10, 1);
  ViewGeometry g = view_geometry(view, 1.0f, glm::vec3(0), 2.0f);
  EXPECT_NEAR(g.ahead_m, 10.0, 1e-6);
  EXPECT_NEAR(g.radius_m, 2.0, 1e-6);
  EXPECT_DOUBLE_EQ(default_pivot_m(g), 2.0);  // at most the radius
  EXPECT_DOUBLE_EQ(fill_offset_m(g), 10.0 - 1.05 * 2.0);
  g.ahead_m -= fill_offset_m(g);
  EXPECT_NEAR(fill_offset_m(g), 0.0, 1e-12);  // already filled
  // Scene units: 100 per metre.
  const ViewGeometry cm = view_geometry(view, 100.0f, glm::vec3(0), 2.0f);
  EXPECT_NEAR(cm.ahead_m, 0.1, 1e-6);
  // Turned around (the centre behind the head): at least half the radius ahead.
  const glm::mat4 back = glm::rotate(view, glm::radians(180.0f), glm::vec3(0, 1, 0));
  const ViewGeometry b = view_geometry(back, 1.0f, glm::vec3(0), 2.0f);
  EXPECT_LT(b.ahead_m, 0);
  EXPECT_DOUBLE_EQ(default_pivot_m(b), 1.0);
  EXPECT_DOUBLE_EQ(fill_offset_m(b), 0.0);
  // Inside large bounds, the centre 3 ahead: the centre.
  EXPECT_DOUBLE_EQ(default_pivot_m(view_geometry(view, 1.0f, glm::vec3(0, 0, 7), 5.0f)), 3.0);
}

}  // namespace

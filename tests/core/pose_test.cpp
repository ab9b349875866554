// The pose algebra: compose, inverse, relative, interpolate.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "foveal/core/pose.hpp"

namespace foveal {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

Pose yaw_pose(float deg, glm::vec3 at = glm::vec3(0.0f)) {
  return {at, glm::angleAxis(deg * kPi / 180.0f, glm::vec3(0, 1, 0))};
}

void expect_near(const Pose& a, const Pose& b, float tol = 1e-6f) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a.position_m[i], b.position_m[i], tol) << i;
  // q and -q are the same rotation.
  const float d = std::abs(glm::dot(a.orientation, b.orientation));
  EXPECT_NEAR(d, 1.0f, tol) << "orientations differ";
}

TEST(Pose, ComposeAppliesTheRightOperandFirst) {
  const Pose a = yaw_pose(90, {1, 0, 0});
  const Pose b{{0, 0, -2}, glm::quat(1, 0, 0, 0)};
  const Pose ab = compose(a, b);
  // b moves the origin 2 m forward; a turns that 90° left (-z -> -x) and adds 1 m of x.
  EXPECT_NEAR(ab.position_m.x, -1.0f, 1e-6f);
  EXPECT_NEAR(ab.position_m.z, 0.0f, 1e-6f);
  EXPECT_EQ(compose(a, Pose{}), a);
}

TEST(Pose, InverseUndoes) {
  const Pose p{{0.3f, 1.2f, -0.5f}, glm::normalize(glm::quat(0.9f, 0.1f, -0.3f, 0.2f))};
  expect_near(compose(p, inverse(p)), Pose{});
  expect_near(compose(inverse(p), p), Pose{});
}

TEST(Pose, RelativeToItselfIsExactlyTheIdentity) {
  const Pose p{{0.97f, 1.18f, -0.55f}, glm::normalize(glm::quat(0.99f, 0.04f, -0.03f, 0.03f))};
  EXPECT_EQ(relative_to(p, p), Pose{});
  // A 10° turn to the right of a pose that was already turned: 10° right, seen from it.
  const Pose base = yaw_pose(30, {1, 1, 1});
  const Pose turned = compose(base, yaw_pose(-10));
  expect_near(relative_to(base, turned), yaw_pose(-10));
}

TEST(Pose, InterpolateEndsAreExactAndTheMiddleIsHalfTheTurn) {
  const Pose a = yaw_pose(0, {0, 0, 0});
  const Pose b = yaw_pose(90, {2, 0, 0});
  EXPECT_EQ(interpolate(a, b, 0.0), a);
  EXPECT_EQ(interpolate(a, b, 1.0), b);
  EXPECT_EQ(interpolate(a, b, -1.0), a);
  EXPECT_EQ(interpolate(a, b, 7.0), b);
  EXPECT_EQ(interpolate(a, b, std::nan("")), a);
  expect_near(interpolate(a, b, 0.5), yaw_pose(45, {1, 0, 0}));
  expect_near(interpolate(a, b, 0.25), yaw_pose(22.5f, {0.5f, 0, 0}));
}

TEST(Pose, InterpolateTakesTheShorterArcWhateverTheQuaternionsSign) {
  const Pose a = yaw_pose(170);
  Pose b = yaw_pose(-170);  // 20° on, across ±180°
  b.orientation = -b.orientation;
  expect_near(interpolate(a, b, 0.5), yaw_pose(180));
}

TEST(Pose, UnitAndFiniteChecks) {
  EXPECT_TRUE(is_unit(glm::quat(1, 0, 0, 0)));
  EXPECT_TRUE(is_unit(glm::quat(0.7071068f, 0, 0.7071068f, 0)));
  EXPECT_FALSE(is_unit(glm::quat(0.5f, 0, 0, 0)));
  EXPECT_FALSE(is_unit(glm::quat(0, 0, 0, 0)));
  EXPECT_FALSE(is_unit(glm::quat(std::nanf(""), 0, 0, 0)));
  Pose p;
  EXPECT_TRUE(is_finite(p));
  p.position_m.y = INFINITY;
  EXPECT_FALSE(is_finite(p));
}

}  // namespace
}  // namespace foveal

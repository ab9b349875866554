// The head pose and the IPD reach the eye cameras (FrameParams::head, ::ipd_mm): real
// frames of the Dungeon scene, image motion measured by matching the frames.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

#include "foveal/render/stereo_camera.hpp"
#include "gl_support.hpp"
#include "test_support.hpp"

using namespace foveal;
using render::Method;

namespace {

constexpr int kEye = 192;  // per-eye viewport, square: 384x192 side by side
constexpr float kPi = std::numbers::pi_v<float>;

render::FrameParams with_head(const Pose& head, double ipd_mm = 0.0) {
  render::FrameParams p = test::frame(Method::full, 1.0);
  p.head = head;
  p.ipd_mm = ipd_mm;
  return p;
}

// Turns to the right (about -y in the runtime's frame: -z forward, y up) or up (about +x).
Pose turn_right(float deg) { return {glm::vec3(0.0f), glm::angleAxis(-deg * kPi / 180.0f, glm::vec3(0, 1, 0))}; }
Pose turn_up(float deg) { return {glm::vec3(0.0f), glm::angleAxis(deg * kPi / 180.0f, glm::vec3(1, 0, 0))}; }

std::vector<float> luma(const image::Image& img, Eye eye) {
  std::vector<float> l(static_cast<std::size_t>(kEye) * kEye);
  const int x0 = eye == Eye::left ? 0 : kEye;
  for (int y = 0; y < kEye; ++y)
    for (int x = 0; x < kEye; ++x) {
      const std::uint8_t* p = img.at(x0 + x, y);
      l[static_cast<std::size_t>(y) * kEye + x] = 0.3f * p[0] + 0.59f * p[1] + 0.11f * p[2];
    }
  return l;
}

// The whole-pixel shift (dx, dy) that best maps `a` onto `b` (b(x + dx, y + dy) ≈ a(x, y)),
// searched over ±kRange on one axis, by the smallest mean absolute difference over the
// central region. Content moving left or up gives a negative shift (y down in images).
constexpr int kRange = 24;
int best_shift(const std::vector<float>& a, const std::vector<float>& b, bool vertical) {
  int best = 0;
  double best_err = 1e30;
  for (int s = -kRange; s <= kRange; ++s) {
    double err = 0;
    for (int y = kRange; y < kEye - kRange; ++y)
      for (int x = kRange; x < kEye - kRange; ++x) {
        const int bx = vertical ? x : x + s, by = vertical ? y + s : y;
        err += std::abs(b[static_cast<std::size_t>(by) * kEye + bx] - a[static_cast<std::size_t>(y) * kEye + x]);
      }
    if (err < best_err) best_err = err, best = s;
  }
  return best;
}

class HeadPoseCamera : public ::testing::Test {
 protected:
  // One compositor and one scene load for the whole suite (the GL context is the process's).
  static void SetUpTestSuite() {
    if (!test::gl_ready()) return;
    compositor_ = new render::Compositor(test::make_compositor(2 * kEye, kEye));
    dungeon_ = new render::Scene(test::scene(test::source_path("data/scenes/Dungeon/dungeon_simplified.gltf")));
  }
  static void TearDownTestSuite() {
    delete dungeon_;
    delete compositor_;
  }
  void SetUp() override { ASSERT_TRUE(test::gl_ready()); }
  image::Image render(const render::FrameParams& p) { return test::render_frame(c(), scene(), p); }

  static inline render::Compositor* compositor_ = nullptr;
  static inline render::Scene* dungeon_ = nullptr;
  static render::Compositor& c() { return *compositor_; }
  static const render::Scene& scene() { return *dungeon_; }
};

TEST_F(HeadPoseCamera, IdentityPoseAndTheModelsIpdAreTheSceneViewExactly) {
  const DisplayModel model = DisplayModel::vive_pro_eye();
  for (Eye e : kEyes) {
    // The camera before the pose existed: the view file's head, half the model's IPD aside.
    const float half_ipd = 0.5f * model.ipd_mm / 1000.0f * scene().view.units_per_meter;
    const glm::mat4 old_view = glm::inverse(scene().view.head_to_world *
                                            glm::translate(glm::mat4(1.0f), glm::vec3((e == Eye::left ? -1.0f : 1.0f) * half_ipd, 0, 0)));
    const render::EyeView v = render::eye_view(scene(), model, e, Pose{}, model.ipd_mm);
    EXPECT_EQ(std::memcmp(&v.view, &old_view, sizeof old_view), 0) << eye_name(e);
  }
  const image::Image base = render(test::frame(Method::full, 1.0));
  EXPECT_EQ(image::max_abs_diff(base, render(with_head(Pose{}, model.ipd_mm))), 0);
  // The relative pose of a recording's first sample is exactly the identity, too.
  const Pose first{{0.97f, 1.18f, -0.55f}, glm::normalize(glm::quat(0.99f, 0.04f, -0.03f, 0.03f))};
  EXPECT_EQ(image::max_abs_diff(base, render(with_head(relative_to(first, first)))), 0);
}

TEST_F(HeadPoseCamera, TurningRightMovesTheImageLeftByTheTurn) {
  const image::Image base = render(test::frame(Method::full, 1.0));
  const image::Image turned = render(with_head(turn_right(5.0f)));
  // A point straight ahead moves to tan(-5°) on the image plane: W · tan 5° / (tan_r - tan_l).
  const DisplayModel model = DisplayModel::vive_pro_eye();
  const double px = kEye * std::tan(5.0 * std::numbers::pi / 180.0) / (model.eye(Eye::left).tan_right - model.eye(Eye::left).tan_left);
  for (Eye e : kEyes) {
    const int s = best_shift(luma(base, e), luma(turned, e), false);
    EXPECT_NEAR(s, -px, 1.5) << eye_name(e);
    EXPECT_EQ(best_shift(luma(base, e), luma(turned, e), true), 0) << eye_name(e);
  }
  // The other way round: the image moves right.
  EXPECT_GT(best_shift(luma(base, Eye::left), luma(render(with_head(turn_right(-5.0f))), Eye::left), false), 0);
}

TEST_F(HeadPoseCamera, LookingUpMovesTheImageDown) {
  const image::Image base = render(test::frame(Method::full, 1.0));
  const image::Image up = render(with_head(turn_up(5.0f)));
  const DisplayModel model = DisplayModel::vive_pro_eye();
  const double px = kEye * std::tan(5.0 * std::numbers::pi / 180.0) / (model.eye(Eye::left).tan_top - model.eye(Eye::left).tan_bottom);
  EXPECT_NEAR(best_shift(luma(base, Eye::left), luma(up, Eye::left), true), px, 1.5);
}

TEST_F(HeadPoseCamera, SteppingRightMovesTheImageLeft) {
  const image::Image base = render(test::frame(Method::full, 1.0));
  const image::Image stepped = render(with_head({glm::vec3(0.3f, 0.0f, 0.0f), glm::quat(1, 0, 0, 0)}));
  for (Eye e : kEyes) EXPECT_LT(best_shift(luma(base, e), luma(stepped, e), false), -1) << eye_name(e);
}

TEST_F(HeadPoseCamera, TheIpdSetsTheEyeSeparation) {
  const image::Image base = render(test::frame(Method::full, 1.0));
  // 200 mm: each eye 68.5 mm further out, so the left eye's image moves right, the right's left.
  const image::Image wide = render(with_head(Pose{}, 200.0));
  EXPECT_GT(best_shift(luma(base, Eye::left), luma(wide, Eye::left), false), 0);
  EXPECT_LT(best_shift(luma(base, Eye::right), luma(wide, Eye::right), false), 0);
  // The left eye at 103 mm sees what it sees at 63 mm with the head 20 mm to the left.
  const image::Image ipd103 = render(with_head(Pose{}, 103.0));
  const image::Image left20 = render(with_head({glm::vec3(-0.02f, 0.0f, 0.0f), glm::quat(1, 0, 0, 0)}, 63.0));
  const image::Rect left_half{0, 0, kEye, kEye};
  EXPECT_GT(image::psnr(ipd103, left20, left_half), 40.0);
  EXPECT_LT(image::psnr(ipd103, base, left_half), image::psnr(ipd103, left20, left_half) - 10.0);
}

TEST_F(HeadPoseCamera, BadPoseOrIpdIsBadInput) {
  render::FrameParams p = with_head(Pose{});
  p.head.position_m.x = std::nanf("");
  auto r = c().render(scene(), p);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::bad_input);
  p = with_head({glm::vec3(0.0f), glm::quat(0, 0, 0, 0)});
  EXPECT_FALSE(c().render(scene(), p));
  for (double ipd : {-1.0, 500.0, static_cast<double>(NAN)}) {
    auto bad = c().render(scene(), with_head(Pose{}, ipd));
    ASSERT_FALSE(bad) << ipd;
    EXPECT_NE(bad.error().message.find("ipd_mm"), std::string::npos);
  }
  // A slightly off-unit orientation (float arithmetic) is renormalised, not refused.
  Pose off = turn_right(5.0f);
  off.orientation *= 1.0004f;
  EXPECT_TRUE(c().render(scene(), with_head(off)));
}

}  // namespace

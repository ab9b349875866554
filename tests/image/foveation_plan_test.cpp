// Foveation plans: every method shades what its level says, layers nest around the
// fovea wherever it is, σ = 1 is full rate, and every point and rectangle is in viewport
// coordinates with the origin top-left (docs/conventions.md).
#include <gtest/gtest.h>

#include <cmath>

#include "foveal/image/foveation_plan.hpp"
#include "foveal/rmfr_mapping.hpp"

using namespace foveal;
using namespace foveal::render;

namespace {
const EyeFrustum kVive = DisplayModel::vive_pro_eye().eye(Eye::left);
constexpr int kW = 1440, kH = 1600;
const double kPositions[9][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0.5, 0}, {0.5, 1}, {0, 0.5}, {1, 0.5}, {0.5, 0.5}};

EyeFoveation at(double sigma, double x, double y) {
  EyeFoveation f;
  f.sigma = sigma;
  f.fovea_x = x;
  f.fovea_y = y;
  return f;
}
}  // namespace

TEST(FoveationPlan, EveryMethodShadesAboutWHOverSigmaSquared) {
  for (Method m : {Method::rmfr, Method::kfr, Method::hyperbolic, Method::linear, Method::uniform, Method::fixed})
    for (double sigma : {1.4, 2.0, 2.6, 3.0, 4.0})
      for (const auto& p : kPositions) {
        auto plan = plan_eye(m, at(sigma, p[0], p[1]), kW, kH, kVive);
        ASSERT_TRUE(plan) << plan.error().message;
        const double target = double(kW) * kH / (sigma * sigma);
        const double shaded = static_cast<double>(plan->shaded_samples());
        EXPECT_LE(shaded, target * 1.01) << method_name(m) << " sigma " << sigma;
        EXPECT_GE(shaded, target * 0.97) << method_name(m) << " sigma " << sigma << " fovea " << p[0] << "," << p[1];
      }
}

TEST(FoveationPlan, LayersNestAroundTheFoveaOnEveryBorder) {
  for (Method m : {Method::hyperbolic, Method::linear})
    for (const auto& p : kPositions) {
      auto plan = plan_eye(m, at(2.6, p[0], p[1]), kW, kH, kVive);
      ASSERT_TRUE(plan);
      const double fx = plan->fovea.x * kW, fy = plan->fovea.y * kH;
      const Layer* prev = nullptr;
      for (const Layer& l : plan->layers) {
        EXPECT_GE(l.x, 0);
        EXPECT_GE(l.y, 0);
        EXPECT_LE(l.x + l.w, kW);
        EXPECT_LE(l.y + l.h, kH);
        EXPECT_GE(fx, l.x - 1e-9);
        EXPECT_LE(fx, l.x + l.w + 1e-9);
        EXPECT_GE(fy, l.y - 1e-9);
        EXPECT_LE(fy, l.y + l.h + 1e-9);
        if (prev) {
          EXPECT_GT(l.ecc_max_deg, prev->ecc_max_deg);
          EXPECT_GE(l.pixel_size, prev->pixel_size);
        }
        prev = &l;
      }
      ASSERT_FALSE(plan->layers.empty());
      EXPECT_TRUE(std::isinf(plan->layers.back().ecc_max_deg));
      EXPECT_EQ(plan->layers.back().w, kW);  // the outermost layer covers the viewport
    }
}

TEST(FoveationPlan, PaperParametersAtScaleOne) {
  EyeFoveation f = at(2.0, 0.5, 0.5);
  f.layer_scale = 1.0;
  auto h = plan_eye(Method::hyperbolic, f, kW, kH, kVive);
  ASSERT_TRUE(h);
  ASSERT_EQ(h->layers.size(), 3u);
  EXPECT_DOUBLE_EQ(h->layers[0].ecc_max_deg, 10.0);
  EXPECT_DOUBLE_EQ(h->layers[1].ecc_max_deg, 20.0);
  EXPECT_DOUBLE_EQ(h->layers[1].pixel_size, 2.0);
  EXPECT_DOUBLE_EQ(h->layers[2].pixel_size, 12.35);
  // 10° around the centre of a 753.6 px focal length: radius 753.6·tan 10° = 133 px.
  EXPECT_NEAR(h->layers[0].w, 2 * 753.6 * std::tan(10 * M_PI / 180) + 2, 3);
  auto l = plan_eye(Method::linear, f, kW, kH, kVive);
  ASSERT_TRUE(l);
  EXPECT_NEAR(l->layers.back().pixel_size, 1 / std::sqrt(0.047), 1e-9);
  EXPECT_DOUBLE_EQ(l->layers[0].ecc_max_deg, 12.0);
}

TEST(FoveationPlan, SigmaOneIsFullRateForEveryMethod) {
  for (Method m : all_methods()) {
    auto p = plan_eye(m, at(1.0, 0.1, 0.9), kW, kH, kVive);
    ASSERT_TRUE(p);
    EXPECT_EQ(p->shaded_samples(), std::size_t(kW) * kH) << method_name(m);
    EXPECT_TRUE(p->method == Method::full || p->method == Method::rmfr);
  }
}

TEST(FoveationPlan, KfrUsesTheFarthestCorner) {
  auto p = plan_eye(Method::kfr, at(2.0, 0.0, 1.0), kW, kH, kVive);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->kfr_log_max, std::log(std::hypot(kW, kH)), 1e-9);
  EXPECT_EQ(p->kfr_alpha, 4.0);
}

TEST(FoveationPlan, EccentricityThroughTheFrustum) {
  EXPECT_NEAR(eccentricity_deg(kVive, {0.5, 0.5}, {0.5, 0.5}), 0.0, 1e-6);
  EXPECT_NEAR(eccentricity_deg(kVive, {0.5, 0.5}, {1.0, 0.5}), std::atan(kVive.tan_right) * 180 / M_PI, 1e-5);
}

// One convention at the render API: a fovea near the top-left corner is where the plan,
// its rectangles, its σ and its eccentricities say it is, in top-left terms.
TEST(FoveationPlan, PointsAndRectanglesAreTopLeft) {
  const glm::dvec2 at_top(0.25, 0.2);
  for (Method m : all_methods()) {
    auto p = plan_eye(m, at(2.6, at_top.x, at_top.y), kW, kH, kVive);
    ASSERT_TRUE(p) << method_name(m);
    EXPECT_EQ(p->sigma, m == Method::full ? 1.0 : 2.6) << method_name(m);  // σ is the plan's
    if (!follows_gaze(m)) continue;
    EXPECT_EQ(p->fovea, at_top) << method_name(m);
    // The innermost layer (inset's inner view, the layered methods' fovea) lies around
    // the fovea, in the upper half.
    if (p->layers.empty()) continue;
    const Layer& inner = p->layers.front();
    EXPECT_LE(inner.y, at_top.y * kH) << method_name(m);
    EXPECT_GE(inner.y + inner.h, at_top.y * kH) << method_name(m);
    EXPECT_LT(inner.y + inner.h, kH / 2) << method_name(m);
  }
  // The inset's inner view is centred on the fovea's row counted from the top.
  auto inset = plan_eye(*parse_method("inset"), at(2.6, at_top.x, at_top.y), kW, kH, kVive);
  ASSERT_TRUE(inset);
  const Layer& in = inset->layers.front();
  EXPECT_NEAR(in.y + 0.5 * in.h, at_top.y * kH, 0.5);
  EXPECT_NEAR(in.x + 0.5 * in.w, at_top.x * kW, 0.5);

  // Through a frustum taller above the axis than below it: the axis lies 0.75 of the way
  // down, the top edge is atan(1.5) away from it, the bottom edge atan(0.5).
  const EyeFrustum tall{-1.0f, 1.0f, -0.5f, 1.5f};
  const glm::dvec2 c = optical_centre(tall);
  EXPECT_DOUBLE_EQ(c.x, 0.5);
  EXPECT_DOUBLE_EQ(c.y, 0.75);
  EXPECT_NEAR(eccentricity_deg(tall, c, {0.5, 0.0}), std::atan(1.5) * 180 / M_PI, 1e-9);
  EXPECT_NEAR(eccentricity_deg(tall, c, {0.5, 1.0}), std::atan(0.5) * 180 / M_PI, 1e-9);
  auto fixed = plan_eye(Method::fixed, at(2.6, at_top.x, at_top.y), kW, kH, tall);
  ASSERT_TRUE(fixed);
  EXPECT_EQ(fixed->fovea, c);
}

TEST(FoveationPlan, RejectsBadLevels) {
  EXPECT_FALSE(plan_eye(Method::rmfr, at(0.5, 0.5, 0.5), kW, kH, kVive));
  EXPECT_FALSE(plan_eye(Method::kfr, at(NAN, 0.5, 0.5), kW, kH, kVive));
  EyeFoveation f = at(2, 0.5, 0.5);
  f.kfr_alpha = 0;
  EXPECT_FALSE(plan_eye(Method::kfr, f, kW, kH, kVive));
  f = at(2, 0.5, 0.5);
  f.layer_scale = -1;
  EXPECT_FALSE(plan_eye(Method::linear, f, kW, kH, kVive));
  EXPECT_FALSE(parse_method("foo"));
  EXPECT_EQ(*parse_method("hyperbolic"), Method::hyperbolic);
}

TEST(FoveationPlan, UnknownMethodsAreErrorsNamingTheKnownOnes) {
  EXPECT_EQ(method_names_joined(","), "full,rmfr,kfr,hyperbolic,linear,uniform,fixed,inset,inset-fixed");
  ASSERT_EQ(method_names().size(), all_methods().size());
  for (std::size_t i = 0; i < all_methods().size(); ++i) {
    EXPECT_EQ(method_names()[i], method_name(all_methods()[i]));
    EXPECT_EQ(*parse_method(method_names()[i]), all_methods()[i]);
  }
  auto bad = parse_method("RMFR");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("'RMFR' (full, rmfr, kfr, hyperbolic, linear, uniform, fixed, inset, inset-fixed)"), std::string::npos) << bad.error().message;
  // An enum value from elsewhere (a cast, a newer peer) plans nothing, at any level.
  const Method unknown = static_cast<Method>(42);
  EXPECT_FALSE(is_method(unknown));
  for (double sigma : {1.0, 2.6}) {
    auto p = plan_eye(unknown, at(sigma, 0.5, 0.5), kW, kH, kVive);
    ASSERT_FALSE(p);
    EXPECT_NE(p.error().message.find("unknown foveation method 42"), std::string::npos) << p.error().message;
  }
}

TEST(FoveationPlan, UniformIsRmfrsBufferWithTheIdentityMap) {
  for (double sigma : {1.4, 2.6})
    for (const auto& p : kPositions) {
      auto u = plan_eye(Method::uniform, at(sigma, p[0], p[1]), kW, kH, kVive);
      auto r = plan_eye(Method::rmfr, at(sigma, p[0], p[1]), kW, kH, kVive);
      ASSERT_TRUE(u && r);
      EXPECT_EQ(u->method, Method::uniform);
      EXPECT_EQ(u->buffer_w, r->buffer_w);
      EXPECT_EQ(u->buffer_h, r->buffer_h);
      EXPECT_EQ(u->f.x, rmfr::kRmfrIdentityF);
      EXPECT_EQ(u->f.y, rmfr::kRmfrIdentityF);
      // The identity map: every screen position lands on itself in the buffer.
      for (double q : {0.0, 0.1, 0.37, 0.5, 0.9, 1.0}) EXPECT_DOUBLE_EQ(rmfr::rmfr_forward(q, u->fovea.x, u->f.x), q);
      EXPECT_TRUE(u->layers.empty());
      EXPECT_EQ(u->fovea, optical_centre(kVive));  // whatever the gaze
    }
  EXPECT_FALSE(follows_gaze(Method::uniform));
}

TEST(FoveationPlan, FixedPinsTheFoveaAtTheOpticalCentreWhateverTheGaze) {
  // An asymmetric frustum (the original Vive's measured left eye): the optical axis is
  // off the viewport's centre.
  const EyeFrustum vive{-1.397f, 1.251f, -1.478f, 1.464f};
  const glm::dvec2 c = optical_centre(vive);
  EXPECT_NEAR(c.x, 1.397 / (1.397 + 1.251), 1e-6);
  EXPECT_NEAR(c.y, 1.464 / (1.478 + 1.464), 1e-6);  // from the top edge
  EXPECT_NEAR(optical_centre(kVive).x, 0.5, 1e-9);
  for (const auto& p : kPositions) {
    auto f = plan_eye(Method::fixed, at(2.6, p[0], p[1]), kW, kH, vive);
    auto r = plan_eye(Method::rmfr, at(2.6, p[0], p[1]), kW, kH, vive);
    ASSERT_TRUE(f && r);
    EXPECT_EQ(f->method, Method::fixed);
    EXPECT_DOUBLE_EQ(f->fovea.x, c.x);
    EXPECT_DOUBLE_EQ(f->fovea.y, c.y);
    EXPECT_EQ(f->f, r->f);
    EXPECT_EQ(f->shaded_samples(), r->shaded_samples());
  }
  EXPECT_FALSE(follows_gaze(Method::fixed));
  EXPECT_FALSE(follows_gaze(Method::full));
  EXPECT_TRUE(follows_gaze(Method::rmfr));
  EXPECT_TRUE(follows_gaze(Method::kfr));
}

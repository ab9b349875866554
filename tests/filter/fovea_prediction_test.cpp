// predict_fovea (runtime/fovea) and the velocity and verdict GazePipeline hands it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "foveal/runtime/fovea_prediction.hpp"
#include "foveal/runtime/gaze_pipeline.hpp"

namespace foveal {
namespace {

constexpr TimeNs kDt = 8'333'333;  // 120 Hz

GazeSample sample_at(TimeNs t, double u, double v) {
  GazeSample s;
  s.t_ns = t;
  for (EyeSample& e : s.eyes) {
    e.valid = kValidDirection;
    e.direction = glm::normalize(glm::vec3(static_cast<float>(u), static_cast<float>(v), -1.0f));
  }
  return s;
}

// The pixel of tangent-plane point (u, v) in the left eye (the mapping is linear).
glm::vec2 pixel_of(const DisplayModel& m, double u, double v) {
  return m.direction_to_pixel(Eye::left, glm::normalize(glm::vec3(static_cast<float>(u), static_cast<float>(v), -1.0f)));
}

FoveaFrame one_point(glm::vec2 px, glm::vec2 vel, bool predictable, FoveaState st = FoveaState::pursuit) {
  FoveaFrame f;
  f.t_ns = 1'000'000'000;
  f.device_t_ns = 77;
  f.arrival_ns = 1'000'000'500;
  for (FoveaPoint& p : f.eyes) {
    p.px = px;
    p.velocity_px_s = vel;
    p.predictable = predictable;
    p.state = st;
    p.confidence = 1.0f;
  }
  return f;
}

// A steady pursuit along the tangent plane: after the filter has caught up, the
// prediction to t + h lands on the gaze at t + h, while the filter alone trails it.
TEST(FoveaPrediction, ConstantVelocityPursuitIsPredictedExactly) {
  const DisplayModel m = DisplayModel::vive_pro_eye();
  GazePipeline pipe(m, FilterConfig{});
  constexpr double k = 0.4;  // tangent units per second: 14-23 deg/s over the path
  FoveaFrame f;
  TimeNs t = 0;
  for (int i = 0; i < 480; ++i) {  // 4 s from u = -0.8
    t = i * kDt;
    f = pipe.update(sample_at(t, -0.8 + k * static_cast<double>(t) * 1e-9, 0.1));
  }
  const FoveaPoint& p = f.eye(Eye::left);
  ASSERT_EQ(p.state, FoveaState::pursuit);
  ASSERT_TRUE(p.predictable);
  const double u_now = -0.8 + k * static_cast<double>(t) * 1e-9;
  const glm::vec2 px_per_s = pixel_of(m, u_now + k, 0.1) - pixel_of(m, u_now, 0.1);
  EXPECT_NEAR(p.velocity_px_s.x, px_per_s.x, 0.5);
  EXPECT_NEAR(p.velocity_px_s.y, 0.0, 0.5);
  for (TimeNs h : {TimeNs{0} + 1, 11 * kNsPerMs, 22 * kNsPerMs, 45 * kNsPerMs}) {
    const glm::vec2 truth = pixel_of(m, u_now + k * static_cast<double>(h) * 1e-9, 0.1);
    const FoveaFrame q = predict_fovea(f, t + h, m.eye_width, m.eye_height);
    EXPECT_NEAR(q.eye(Eye::left).px.x, truth.x, 0.5) << "h " << h;
    EXPECT_NEAR(q.eye(Eye::left).px.y, truth.y, 0.5) << "h " << h;
    EXPECT_GT(std::abs(p.px.x - truth.x), 4.0f) << "the filter alone trails the pursuit";
  }
}

TEST(FoveaPrediction, ASaccadeIsHeld) {
  const DisplayModel m = DisplayModel::vive_pro_eye();
  GazePipeline pipe(m, FilterConfig{});
  TimeNs t = 0;
  for (int i = 0; i < 60; ++i, t += kDt) pipe.update(sample_at(t, 0.0, 0.0));
  // 400 deg/s to the right: ~0.06 tangent units per sample near the centre.
  bool seen = false;
  for (int i = 1; i <= 5; ++i, t += kDt) {
    const FoveaFrame f = pipe.update(sample_at(t, 0.06 * i, 0.0));
    for (const FoveaPoint& p : f.eyes) {
      if (p.state != FoveaState::saccade) continue;
      seen = true;
      EXPECT_FALSE(p.predictable);
      EXPECT_EQ(p.velocity_px_s, glm::vec2(0.0f));
      const FoveaFrame q = predict_fovea(f, t + 30 * kNsPerMs, m.eye_width, m.eye_height);
      EXPECT_EQ(q.eye(Eye::left).px, f.eye(Eye::left).px);
    }
  }
  EXPECT_TRUE(seen) << "the jump was not taken for a saccade";
}

TEST(FoveaPrediction, BlinkLostAndFilledInEyesAreNotPredicted) {
  const DisplayModel m = DisplayModel::vive_pro_eye();
  GazePipeline pipe(m, FilterConfig{});
  TimeNs t = 0;
  for (int i = 0; i < 60; ++i, t += kDt) pipe.update(sample_at(t, 0.01 * i, 0.0));
  GazeSample closed = sample_at(t, 0.6, 0.0);
  closed.eye(Eye::left).valid = 0;
  FoveaFrame f = pipe.update(closed);
  EXPECT_EQ(f.eye(Eye::left).state, FoveaState::blink);
  EXPECT_FALSE(f.eye(Eye::left).predictable);
  EXPECT_TRUE(f.eye(Eye::right).predictable);
  closed.eye(Eye::right).valid = 0;
  for (int i = 0; i < 40; ++i) f = pipe.update((closed.t_ns += kDt, closed));  // past hold_ms
  EXPECT_EQ(f.eye(Eye::left).state, FoveaState::lost);
  EXPECT_FALSE(f.eye(Eye::left).predictable);
  // One eye back (a snap, then smoothed): the other is filled in from it, and not
  // predicted on its own.
  GazeSample one = sample_at(closed.t_ns + kDt, 0.2, 0.0);
  one.eye(Eye::left).valid = 0;
  f = pipe.update(one);
  EXPECT_FALSE(f.eye(Eye::right).predictable) << "the first sample back is a snap: no velocity yet";
  one.t_ns += kDt;
  f = pipe.update(one);
  EXPECT_TRUE(f.eye(Eye::right).predictable);
  EXPECT_FALSE(f.eye(Eye::left).predictable);
  // Not predictable: unchanged whatever its velocity says.
  const FoveaFrame g = one_point({100, 100}, {5000, 5000}, false, FoveaState::blink);
  EXPECT_EQ(predict_fovea(g, g.t_ns + 20 * kNsPerMs, 1440, 1600).eyes[0].px, glm::vec2(100, 100));
}

TEST(FoveaPrediction, MovesByVelocityTimesHorizonAndKeepsTheSampleTimes) {
  const FoveaFrame f = one_point({700, 800}, {1000, -500}, true);
  const FoveaFrame q = predict_fovea(f, f.t_ns + 20 * kNsPerMs, 1440, 1600);
  EXPECT_FLOAT_EQ(q.eyes[0].px.x, 720.0f);
  EXPECT_FLOAT_EQ(q.eyes[0].px.y, 790.0f);
  EXPECT_EQ(q.t_ns, f.t_ns);
  EXPECT_EQ(q.device_t_ns, f.device_t_ns);
  EXPECT_EQ(q.arrival_ns, f.arrival_ns);
  EXPECT_EQ(q.eyes[0].state, f.eyes[0].state);
  EXPECT_EQ(q.eyes[0].velocity_px_s, f.eyes[0].velocity_px_s);
}

TEST(FoveaPrediction, TheHorizonIsClamped) {
  const FoveaFrame f = one_point({700, 800}, {1000, 0}, true);
  FoveaPrediction p;
  p.max_horizon_ns = 50 * kNsPerMs;
  EXPECT_FLOAT_EQ(predict_fovea(f, f.t_ns + kNsPerSec, 1440, 1600, p).eyes[0].px.x, 750.0f);
  EXPECT_FLOAT_EQ(predict_fovea(f, f.t_ns - 30 * kNsPerMs, 1440, 1600, p).eyes[0].px.x, 700.0f) << "never backwards";
  EXPECT_FLOAT_EQ(predict_fovea(f, std::numeric_limits<TimeNs>::max(), 1440, 1600, p).eyes[0].px.x, 750.0f);
  EXPECT_FLOAT_EQ(predict_fovea(f, std::numeric_limits<TimeNs>::min(), 1440, 1600, p).eyes[0].px.x, 700.0f);
  p.max_horizon_ns = -5;
  EXPECT_FLOAT_EQ(predict_fovea(f, f.t_ns + kNsPerSec, 1440, 1600, p).eyes[0].px.x, 700.0f);
}

TEST(FoveaPrediction, StaysInsideTheViewport) {
  const FoveaFrame f = one_point({1430, 5}, {5000, -5000}, true);
  const FoveaFrame q = predict_fovea(f, f.t_ns + 40 * kNsPerMs, 1440, 1600);
  EXPECT_LT(q.eyes[0].px.x, 1440.0f);
  EXPECT_GE(q.eyes[0].px.x, 1439.0f);
  EXPECT_EQ(q.eyes[0].px.y, 0.0f);
  // A velocity that carries the point beyond float's range still lands on the edge.
  FoveaPrediction long_horizon;
  long_horizon.max_horizon_ns = 1000 * kNsPerSec;
  const FoveaFrame far =
      predict_fovea(one_point({10, 10}, {3e38f, -3e38f}, true), f.t_ns + 100 * kNsPerSec, 1440, 1600, long_horizon);
  EXPECT_EQ(far.eyes[0].px, glm::vec2(std::nextafter(1440.0f, 0.0f), 0.0f));
}

TEST(FoveaPrediction, NonFiniteInputLeavesTheEyeUnchanged) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  for (glm::vec2 vel : {glm::vec2(nan, 0), glm::vec2(0, inf), glm::vec2(-inf, nan)}) {
    const FoveaFrame q = predict_fovea(one_point({300, 400}, vel, true), 1'020'000'000, 1440, 1600);
    EXPECT_EQ(q.eyes[0].px, glm::vec2(300, 400));
  }
  const FoveaFrame q = predict_fovea(one_point({nan, 400}, {10, 10}, true), 1'020'000'000, 1440, 1600);
  EXPECT_TRUE(std::isnan(q.eyes[0].px.x));
  FoveaFrame lagged = one_point({300, 400}, {0, 0}, true);
  lagged.eyes[0].lag_px = {nan, 0};
  EXPECT_EQ(predict_fovea(lagged, 1'020'000'000, 1440, 1600).eyes[0].px, glm::vec2(300, 400));
  EXPECT_EQ(predict_fovea(one_point({300, 400}, {10, 10}, true), 1'020'000'000, 0, 1600).eyes[0].px,
            glm::vec2(300, 400));
}

TEST(FoveaPrediction, DisabledIsTheIdentity) {
  FoveaFrame f = one_point({700, 800}, {1000, -500}, true);
  f.eyes[1].lag_px = {3, 4};
  FoveaPrediction off;
  off.enabled = false;
  const FoveaFrame q = predict_fovea(f, f.t_ns + 20 * kNsPerMs, 1440, 1600, off);
  for (int e = 0; e < 2; ++e) {
    EXPECT_EQ(q.eyes[e].px, f.eyes[e].px);
    EXPECT_EQ(q.eyes[e].lag_px, f.eyes[e].lag_px);
  }
  EXPECT_EQ(q.t_ns, f.t_ns);
}

}  // namespace
}  // namespace foveal

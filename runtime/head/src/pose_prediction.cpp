#include "foveal/runtime/pose_prediction.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "foveal/runtime/orientation_filter.hpp"

namespace foveal {

namespace {
constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
constexpr std::size_t kMaxPending = 1024;       // a stalled pose source must not grow this
constexpr std::size_t kMaxScored = 1'000'000;   // hours of frames; then the oldest half goes
}  // namespace

Pose predict_pose(const MotionEstimate& m, TimeNs t_ns) {
  if (!m.valid || t_ns <= m.pose.t_ns) return m.pose.pose;
  const float dt = static_cast<float>(std::min(t_ns - m.pose.t_ns, kMaxHorizonNs)) * 1e-9f;
  Pose p = m.pose.pose;
  p.orientation = glm::normalize(p.orientation * rotation_vector_to_quat(m.angular_velocity * dt));
  p.position_m += m.velocity_m_s * dt;
  return p;
}

void PredictionErrors::add(TimeNs t_ns, const Pose& predicted, const Pose& held) {
  if (pending_.size() >= kMaxPending) pending_.pop_front();
  pending_.push_back({t_ns, predicted, held});
}

void PredictionErrors::resolve(const PoseTrack& track) {
  const auto newest = track.newest();
  if (!newest) return;
  while (!pending_.empty() && pending_.front().t_ns <= newest->t_ns) {
    const Pending p = pending_.front();
    pending_.pop_front();
    const Pose actual = track.pose_at(p.t_ns).pose;
    if (angle_deg_.size() >= kMaxScored) {
      for (auto* v : {&angle_deg_, &position_mm_, &held_angle_deg_}) v->erase(v->begin(), v->begin() + kMaxScored / 2);
    }
    angle_deg_.push_back(angle_between(p.predicted.orientation, actual.orientation) * kRadToDeg);
    position_mm_.push_back(double(glm::length(p.predicted.position_m - actual.position_m)) * 1000.0);
    held_angle_deg_.push_back(angle_between(p.held.orientation, actual.orientation) * kRadToDeg);
  }
}

PredictionErrors::Figures PredictionErrors::figures(std::vector<double> v) {
  Figures f;
  f.count = v.size();
  if (v.empty()) return f;
  std::sort(v.begin(), v.end());
  const auto q = [&](double p) { return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))]; };
  f.p50 = q(0.5);
  f.p99 = q(0.99);
  f.max = v.back();
  return f;
}

}  // namespace foveal

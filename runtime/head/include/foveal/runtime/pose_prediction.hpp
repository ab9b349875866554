#pragma once
// The head pose at a frame's expected display time, and how far that prediction was
// from the pose that was then measured (docs/headset.md, "Prediction").
//
// Constant velocity from the newest measurement: the orientation turns at the newest
// angular velocity (the gyro, bias removed; body frame), the position moves at the
// velocity of the last two tracked positions. Horizons are capped (kMaxHorizonNs):
// past that a stale pose is held rather than flung away.
#include <cstdint>
#include <deque>
#include <vector>

#include <glm/vec3.hpp>

#include "foveal/core/pose.hpp"
#include "foveal/core/pose_track.hpp"

namespace foveal {

struct MotionEstimate {
  bool valid = false;
  TimedPose pose{};                    ///< the newest measured pose
  glm::vec3 angular_velocity{0.0f};    ///< rad/s, head frame
  glm::vec3 velocity_m_s{0.0f};        ///< world frame
};

constexpr TimeNs kMaxHorizonNs = 100 * kNsPerMs;

/// `m.pose` carried forward to time `t_ns` (not backwards: t before the pose returns
/// it unchanged), at most kMaxHorizonNs ahead.
Pose predict_pose(const MotionEstimate& m, TimeNs t_ns);

/// Predicted against measured, once the measurement for a predicted time is in.
/// Not thread-safe: the render thread owns it.
class PredictionErrors {
 public:
  /// Remembers what was predicted for display time `t_ns`; `held` is the pose the frame
  /// would have used without prediction (the newest measured one), for comparison.
  void add(TimeNs t_ns, const Pose& predicted, const Pose& held);
  /// Scores every remembered prediction whose time `track` now covers (its newest pose
  /// is at or after it) against track.pose_at(t).
  void resolve(const PoseTrack& track);

  struct Figures {
    std::size_t count = 0;
    double p50 = 0, p99 = 0, max = 0;
  };
  Figures angle_deg() const { return figures(angle_deg_); }
  Figures position_mm() const { return figures(position_mm_); }
  /// The same for the held (unpredicted) pose: what prediction saved.
  Figures held_angle_deg() const { return figures(held_angle_deg_); }
  std::size_t pending() const { return pending_.size(); }
  /// Forgets the predictions not scored yet: the pose source stopped (held, unplugged),
  /// so what gets measured for their times next is no test of the prediction.
  void drop_pending() { pending_.clear(); }

 private:
  struct Pending {
    TimeNs t_ns;
    Pose predicted, held;
  };
  static Figures figures(std::vector<double> v);
  std::deque<Pending> pending_;
  std::vector<double> angle_deg_, position_mm_, held_angle_deg_;
};

}  // namespace foveal

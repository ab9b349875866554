#pragma once
// A short history of timed head poses that one or more producer threads push into and
// the render thread samples at a frame's time (docs/conventions.md, "Head pose").
#include <array>
#include <cstdint>
#include <mutex>
#include <optional>

#include "foveal/core/pose_source.hpp"

namespace foveal {

/// pose_at(t): interpolated between the two pushed poses that bracket t (position
/// lerped, orientation slerped), held at the oldest kept pose before it and at the
/// newest after it (no extrapolation), invalid while nothing has been pushed. The
/// anchor of PoseAt::relative is the first pose pushed since construction or reset().
/// At a pushed pose's own time it returns that pose bit for bit, so a frame drawn for a
/// gaze sample (FoveaFrame::t_ns) gets exactly the pose recorded with it;
/// pose_at(std::numeric_limits<TimeNs>::max()) is the newest pose.
///
/// Thread safety: every member may be called from any thread. One mutex guards the
/// ring and is held only to copy one pose in (push) or to find and copy two out
/// (pose_at, a binary search over at most kCapacity entries): the render thread never
/// waits for more than that.
class PoseTrack final : public PoseSource {
 public:
  /// Poses kept: ~2 s at 120 Hz, ~0.25 s of a 1 kHz IMU.
  static constexpr std::size_t kCapacity = 256;

  /// Adds a pose on the runtime clock. Returns false, and drops it, when its time does
  /// not come after the newest pose's or when it is not finite or its orientation is not
  /// a unit quaternion (is_unit); a kept orientation is renormalised (renormalized()).
  bool push(const TimedPose& p);
  PoseAt pose_at(TimeNs t_ns) const override;
  /// The newest pose pushed (nullopt: none yet). Its time says how fresh the track is.
  std::optional<TimedPose> newest() const;
  /// The anchor of PoseAt::relative (nullopt: no pose pushed yet).
  std::optional<Pose> anchor() const;
  /// Forgets every pose and the anchor (e.g. a new source).
  void reset();
  /// Poses accepted and dropped by push() since construction.
  std::uint64_t accepted() const;
  std::uint64_t dropped() const;

 private:
  const TimedPose& at(std::size_t k) const { return ring_[(first_ + k) % kCapacity]; }  // k-th oldest

  mutable std::mutex mutex_;
  std::array<TimedPose, kCapacity> ring_{};
  std::size_t first_ = 0, count_ = 0;
  Pose anchor_{};
  std::uint64_t accepted_ = 0, dropped_ = 0;
};

}  // namespace foveal

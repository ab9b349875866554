#include "foveal/core/pose_track.hpp"

namespace foveal {

bool PoseTrack::push(const TimedPose& p) {
  const bool usable = is_finite(p.pose) && is_unit(p.pose.orientation);
  TimedPose kept = p;
  if (usable) kept.pose.orientation = renormalized(p.pose.orientation);
  std::lock_guard lock(mutex_);
  if (!usable || (count_ > 0 && p.t_ns <= at(count_ - 1).t_ns)) {
    ++dropped_;
    return false;
  }
  if (count_ == 0) anchor_ = kept.pose;  // the first pose since construction or reset()
  if (count_ == kCapacity) {
    ring_[first_] = kept;  // overwrite the oldest
    first_ = (first_ + 1) % kCapacity;
  } else {
    ring_[(first_ + count_) % kCapacity] = kept;
    ++count_;
  }
  ++accepted_;
  return true;
}

PoseAt PoseTrack::pose_at(TimeNs t_ns) const {
  TimedPose a, b;
  Pose anchor;
  {
    std::lock_guard lock(mutex_);
    if (count_ == 0) return {};
    anchor = anchor_;
    if (t_ns >= at(count_ - 1).t_ns) {
      a = b = at(count_ - 1);
    } else if (t_ns <= at(0).t_ns) {
      a = b = at(0);
    } else {
      // The first kept pose later than t; at(0) <= t < at(count_ - 1) brackets it.
      std::size_t lo = 1, hi = count_ - 1;
      while (lo < hi) {
        const std::size_t mid = (lo + hi) / 2;
        if (at(mid).t_ns > t_ns) hi = mid;
        else lo = mid + 1;
      }
      a = at(lo - 1);
      b = at(lo);
    }
  }
  PoseAt r;
  r.valid = true;
  r.t_ns = t_ns;
  r.pose = b.t_ns == a.t_ns ? a.pose
                            : interpolate(a.pose, b.pose, static_cast<double>(t_ns - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns));
  r.relative = relative_to(anchor, r.pose);
  return r;
}

std::optional<TimedPose> PoseTrack::newest() const {
  std::lock_guard lock(mutex_);
  if (count_ == 0) return std::nullopt;
  return at(count_ - 1);
}

std::optional<Pose> PoseTrack::anchor() const {
  std::lock_guard lock(mutex_);
  if (count_ == 0) return std::nullopt;
  return anchor_;
}

void PoseTrack::reset() {
  std::lock_guard lock(mutex_);
  first_ = count_ = 0;
  anchor_ = Pose{};
}

std::uint64_t PoseTrack::accepted() const {
  std::lock_guard lock(mutex_);
  return accepted_;
}

std::uint64_t PoseTrack::dropped() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

}  // namespace foveal

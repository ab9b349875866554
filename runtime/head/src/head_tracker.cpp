#include "foveal/runtime/head_tracker.hpp"

namespace foveal {

const char* head_state_name(HeadState s) {
  switch (s) {
    case HeadState::waiting: return "waiting";
    case HeadState::tracking: return "tracking";
    case HeadState::held: return "held";
    case HeadState::reconnecting: return "reconnecting";
    case HeadState::stopped: return "stopped";
  }
  return "?";
}

HeadTracker::HeadTracker(PoseDevice& device, bool wait_for_device, OrientationFilterParams filter)
    : device_(device), wait_(wait_for_device), filter_(filter) {}

HeadTracker::~HeadTracker() { stop(); }

void HeadTracker::start() {
  if (thread_.joinable()) return;
  stop_ = false;
  thread_ = std::thread([this] { run(); });
}

void HeadTracker::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void HeadTracker::run() {
  const auto should_stop = [this] { return stop_.load(); };
  if (wait_ && !reopen_with_backoff(device_, should_stop)) {
    std::lock_guard lock(mutex_);
    stats_.state = HeadState::stopped;
    return;
  }
  // IMU-only devices: the filter's orientation is the pose.
  bool fuse = !device_.info().orientation;
  {
    std::lock_guard lock(mutex_);
    stats_.device = device_.info();
  }
  while (!stop_) {
    const PoseReading r = device_.next(std::chrono::milliseconds(50));
    if (r.status == ReadStatus::sample) {
      handle(r, fuse);
      continue;
    }
    std::unique_lock lock(mutex_);
    if (r.status == ReadStatus::timeout) ++stats_.timeouts;
    if (r.status == ReadStatus::disconnected || r.status == ReadStatus::error) {
      ++stats_.disconnects;
      stats_.last_error = r.error.message;
      stats_.state = HeadState::reconnecting;  // the track keeps (holds) the last pose
      lock.unlock();
      if (!reopen_with_backoff(device_, should_stop)) break;
      lock.lock();
      ++stats_.reconnects;
      stats_.device = device_.info();
      motion_.velocity_m_s = glm::vec3(0.0f);  // from the poses before the gap: stale
      // The filter keeps its orientation and bias: the gap is not integrated, and the
      // head starts from where it was held.
      lock.unlock();
      have_position_ = false;
      fuse = !device_.info().orientation;  // `auto` may have found another headset
      continue;
    }
    if (stats_.state == HeadState::tracking && monotonic_now_ns() - stats_.last_reading_ns > kHeldAfterNs)
      stats_.state = HeadState::held;
  }
  std::lock_guard lock(mutex_);
  stats_.state = HeadState::stopped;
}

void HeadTracker::handle(const PoseReading& r, bool fuse) {
  TimedPose measured{};
  bool have_pose = false;
  if (r.has_imu) {
    filter_.update(r.imu);
    if (fuse && filter_.initialised()) {
      measured = {r.imu.t_ns, Pose{glm::vec3(0.0f), filter_.orientation()}};
      have_pose = true;
    }
  }
  glm::vec3 velocity(0.0f);
  bool have_velocity = false;
  if (r.has_pose) {
    measured = r.pose;
    have_pose = true;
    if (have_position_ && r.pose.t_ns > last_position_.t_ns) {
      velocity = (r.pose.pose.position_m - last_position_.pose.position_m) /
                 (static_cast<float>(r.pose.t_ns - last_position_.t_ns) * 1e-9f);
      have_velocity = true;
    }
    last_position_ = r.pose;
    have_position_ = true;
  }
  const bool pushed = have_pose && track_.push(measured);
  std::lock_guard lock(mutex_);
  if (r.has_imu) {
    ++stats_.imu_samples;
    stats_.gyro_bias = filter_.gyro_bias();
    motion_.angular_velocity = filter_.angular_velocity();
  }
  if (pushed) {
    ++stats_.poses;
    motion_.valid = true;
    motion_.pose = measured;
    if (have_velocity) motion_.velocity_m_s = velocity;
  }
  stats_.last_reading_ns = monotonic_now_ns();
  if (motion_.valid) stats_.state = HeadState::tracking;
}

PoseAt HeadTracker::predicted(TimeNs t_ns) const {
  MotionEstimate m;
  {
    std::lock_guard lock(mutex_);
    m = motion_;
    // Nothing new for a while: hold the last pose instead of extrapolating its motion.
    if (monotonic_now_ns() - stats_.last_reading_ns > kHeldAfterNs) m.angular_velocity = m.velocity_m_s = glm::vec3(0.0f);
  }
  const auto anchor = track_.anchor();
  if (!m.valid || !anchor) return {};
  PoseAt p;
  p.valid = true;
  p.t_ns = t_ns;
  p.pose = predict_pose(m, t_ns);
  p.relative = relative_to(*anchor, p.pose);
  return p;
}

MotionEstimate HeadTracker::motion() const {
  std::lock_guard lock(mutex_);
  return motion_;
}

HeadTrackerStats HeadTracker::stats() const {
  std::lock_guard lock(mutex_);
  HeadTrackerStats s = stats_;
  if (s.state == HeadState::tracking && monotonic_now_ns() - s.last_reading_ns > kHeldAfterNs) s.state = HeadState::held;
  return s;
}

}  // namespace foveal

#pragma once
// The pose thread: reads a headset's PoseDevice, fuses IMU-only orientation
// (OrientationFilter), feeds a PoseTrack and keeps the motion needed to predict the
// pose at a frame's display time. Rides out unplugs like the gaze loop
// (reopen_with_backoff); meanwhile the last pose is held and state() says so.
#include <atomic>
#include <mutex>
#include <string>
#include <thread>

#include "foveal/core/pose_device.hpp"
#include "foveal/core/pose_track.hpp"
#include "foveal/runtime/orientation_filter.hpp"
#include "foveal/runtime/pose_prediction.hpp"

namespace foveal {

/// waiting: no pose yet (device absent or silent); tracking: poses arrive; held: none
/// for kHeldAfterNs, the last one is held; reconnecting: the device went away, the last
/// pose is held while it is reopened; stopped.
enum class HeadState { waiting, tracking, held, reconnecting, stopped };
const char* head_state_name(HeadState s);

struct HeadTrackerStats {
  HeadState state = HeadState::waiting;
  PoseDeviceInfo device;
  std::uint64_t poses = 0, imu_samples = 0, timeouts = 0, disconnects = 0, reconnects = 0;
  TimeNs last_reading_ns = 0;  ///< runtime time of the newest reading (0: none)
  std::string last_error;
  glm::vec3 gyro_bias{0.0f};   ///< the filter's estimate (IMU devices)
};

class HeadTracker {
 public:
  /// A pose counts as held once nothing arrived for this long.
  static constexpr TimeNs kHeldAfterNs = 100 * kNsPerMs;

  /// `device` must outlive the tracker. With `wait_for_device` the thread opens it
  /// itself, retrying until it is there; otherwise it is open and started already.
  explicit HeadTracker(PoseDevice& device, bool wait_for_device = true, OrientationFilterParams filter = {});
  ~HeadTracker();
  HeadTracker(const HeadTracker&) = delete;
  HeadTracker& operator=(const HeadTracker&) = delete;

  void start();
  void stop();  ///< joins the thread (within ~60 ms)

  /// Any thread. The measured (fused) poses.
  const PoseTrack& track() const { return track_; }
  /// Any thread: the pose at `t_ns` carried forward from the newest measurement
  /// (predict_pose), relative to the track's anchor; invalid before the first pose.
  PoseAt predicted(TimeNs t_ns) const;
  MotionEstimate motion() const;
  HeadTrackerStats stats() const;

 private:
  void run();
  void handle(const PoseReading& r, bool fuse);

  PoseDevice& device_;
  bool wait_;
  OrientationFilter filter_;  // pose thread only
  PoseTrack track_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;  // guards motion_ and stats_
  MotionEstimate motion_;
  HeadTrackerStats stats_;
  TimedPose last_position_{};  // pose thread: for the velocity of tracked positions
  bool have_position_ = false;
};

}  // namespace foveal

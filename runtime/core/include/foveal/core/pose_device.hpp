#pragma once
// The interface every head-pose driver implements (psvr2, vive; drivers/probe lists
// them): the same lifecycle as GazeSource, delivering the headset's own poses (6DoF
// tracking) and/or inertial samples (IMU) instead of gaze. The runtime turns these into
// a PoseTrack (fusion for IMU-only headsets, docs/headset.md).
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

#include "foveal/core/gaze_source.hpp"
#include "foveal/core/imu_sample.hpp"
#include "foveal/core/pose.hpp"

namespace foveal {

/// What a pose driver's device provides.
struct PoseDeviceInfo {
  std::string driver;  ///< "psvr2", "vive"
  std::string name;    ///< human-readable device name
  std::string path;    ///< device node or usb:BUS:ADDRESS, "" before open()
  std::uint16_t vendor_id = 0, product_id = 0;
  bool position = false;     ///< delivers tracked positions (6DoF)
  bool orientation = false;  ///< delivers tracked orientations (without fusion)
  bool imu = false;          ///< delivers IMU samples
  double imu_rate_hz = 0;    ///< nominal, 0 unknown
};

/// One read. status == sample: at least one of has_pose / has_imu is set.
struct PoseReading {
  ReadStatus status = ReadStatus::timeout;
  bool has_pose = false;
  TimedPose pose{};  ///< tracking frame, runtime clock
  bool has_imu = false;
  ImuSample imu{};
  Error error{};
};

/// Lifecycle: open() -> start() -> next()* -> stop() -> close(), from one thread at a
/// time; none of the calls throws. Malformed device data is counted and skipped.
class PoseDevice {
 public:
  virtual ~PoseDevice() = default;
  virtual Status open() = 0;
  virtual void close() = 0;
  virtual Status start() = 0;
  virtual void stop() = 0;
  /// Blocks at most `timeout` for the next reading. Times are on the runtime clock.
  virtual PoseReading next(std::chrono::nanoseconds timeout) = 0;
  virtual PoseDeviceInfo info() const = 0;
};

/// Device loss, as for gaze sources: close, then open() + start() with the same
/// backoff as reopen_with_backoff(GazeSource&) until it works or `should_stop`.
bool reopen_with_backoff(PoseDevice& device, const std::function<bool()>& should_stop);

}  // namespace foveal

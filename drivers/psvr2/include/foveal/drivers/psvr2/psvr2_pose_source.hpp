#pragma once
// The PlayStation VR2's head tracking as a PoseDevice: SLAM poses (6DoF, the
// headset's own inside-out tracking) from interface 3 and IMU samples (2 kHz, used for
// prediction) from the status interface 7, read with asynchronous libusb transfers on
// its own handle (the gaze driver's interface 5 stays free). Untested against a
// headset: the record parsers are unit-tested on synthesised bytes, the whole driver
// runs against an emulated gadget in the VM suite.
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "foveal/core/device_clock.hpp"
#include "foveal/core/pose_device.hpp"
#include "foveal/core/problem_throttle.hpp"
#include "foveal/drivers/psvr2/psvr2_gaze_packet.hpp"
#include "foveal/drivers/psvr2/psvr2_pose_records.hpp"

struct libusb_context;
struct libusb_device_handle;
struct libusb_transfer;

namespace foveal::usb {

struct Psvr2PoseOptions {
  std::function<void(const std::string&)> log;  ///< default: stderr, rate-limited
};

struct Psvr2PoseCounters {
  std::uint64_t status_transfers = 0, slam_transfers = 0, imu_samples = 0, poses = 0, malformed = 0, disconnects = 0;
  std::uint8_t ipd_mm = 0;  ///< the IPD dial, as last reported (0: not yet)
  std::string last_problem;
};

class Psvr2PoseSource final : public PoseDevice {
 public:
  explicit Psvr2PoseSource(Psvr2PoseOptions opts = {});
  ~Psvr2PoseSource() override;
  Psvr2PoseSource(const Psvr2PoseSource&) = delete;
  Psvr2PoseSource& operator=(const Psvr2PoseSource&) = delete;

  Status open() override;
  void close() override;
  Status start() override;
  void stop() override;
  PoseReading next(std::chrono::nanoseconds timeout) override;
  PoseDeviceInfo info() const override;
  const Psvr2PoseCounters& counters() const { return counters_; }

 private:
  struct Transfer;
  void on_status(const std::uint8_t* data, int length, TimeNs arrival);
  void on_slam(const std::uint8_t* data, int length, TimeNs arrival);
  static void callback(libusb_transfer* t);
  void problem(std::string message);

  Psvr2PoseOptions opts_;
  libusb_context* ctx_ = nullptr;
  libusb_device_handle* handle_ = nullptr;
  bool claimed_status_ = false, claimed_slam_ = false, started_ = false, gone_ = false;
  std::uint8_t status_ep_ = psvr2::kStatusEndpoint, slam_ep_ = psvr2::kSlamEndpoint;
  bool status_interrupt_ = true, slam_interrupt_ = false;
  std::string path_;
  std::vector<std::unique_ptr<Transfer>> transfers_;
  std::deque<PoseReading> queue_;
  WrapCounter wrap_;
  DeviceClock clock_;
  Psvr2PoseCounters counters_;
  ProblemThrottle problems_;
};

}  // namespace foveal::usb

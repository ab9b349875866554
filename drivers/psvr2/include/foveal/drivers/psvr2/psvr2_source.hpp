#pragma once
// The PlayStation VR2 gaze stream through libusb-1.0: claims interface 5, enables the
// stream, reads gaze records from bulk endpoint 0x85 and keeps the stream alive.
// Untested against a headset (none here): the record parser is unit-tested on
// synthetic records; the enable/keep-alive request follows public reverse engineering.
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "foveal/core/gaze_source.hpp"
#include "foveal/core/problem_throttle.hpp"
#include "foveal/drivers/psvr2/psvr2_gaze_packet.hpp"

struct libusb_context;
struct libusb_device_handle;

namespace foveal::usb {

struct Psvr2Options {
  std::function<void(const std::string&)> log;  ///< default: stderr, rate-limited
};

struct Psvr2Counters {
  std::uint64_t transfers = 0, samples = 0, malformed = 0, disconnects = 0;
  std::string last_problem;
};

class Psvr2Source final : public GazeSource {
 public:
  explicit Psvr2Source(Psvr2Options opts = {});
  ~Psvr2Source() override;
  Psvr2Source(const Psvr2Source&) = delete;
  Psvr2Source& operator=(const Psvr2Source&) = delete;

  Status open() override;
  void close() override;
  Status start() override;
  void stop() override;
  ReadResult next(std::chrono::nanoseconds timeout) override;
  SourceInfo info() const override;
  const Psvr2Counters& counters() const { return counters_; }
  /// The bulk IN endpoint in use (0x85 on the headset; read from its descriptors).
  std::uint8_t endpoint() const { return endpoint_; }

 private:
  Status send_gaze_stream(bool enable);
  void problem(std::string message);

  Psvr2Options opts_;
  libusb_context* ctx_ = nullptr;
  libusb_device_handle* handle_ = nullptr;
  bool claimed_ = false, started_ = false;
  std::uint8_t endpoint_ = kPsvr2GazeEndpoint;
  std::string path_;
  std::vector<std::uint8_t> buffer_;
  WrapCounter clock_;
  std::int64_t offset_ns_ = 0;
  bool anchored_ = false;
  TimeNs last_t_ = 0, last_keepalive_ = 0;
  Psvr2Counters counters_;
  ProblemThrottle problems_;
};

}  // namespace foveal::usb

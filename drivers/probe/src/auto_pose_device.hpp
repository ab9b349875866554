#pragma once
// --head auto: whichever headset with a pose is present, chosen again at every open()
// so that a replug (or another headset) is picked up.
#include <optional>

#include "driver_entry.hpp"

namespace foveal::probe {

class AutoPoseDevice final : public PoseDevice {
 public:
  explicit AutoPoseDevice(SourceOptions options) : options_(std::move(options)) {}
  Status open() override;
  void close() override;
  Status start() override;
  void stop() override;
  PoseReading next(std::chrono::nanoseconds timeout) override;
  PoseDeviceInfo info() const override;
  nlohmann::json counters() const;
  std::optional<HeadsetDisplay> display() const;

 private:
  SourceOptions options_;
  std::optional<OpenedPoseDevice> current_;
};

}  // namespace foveal::probe

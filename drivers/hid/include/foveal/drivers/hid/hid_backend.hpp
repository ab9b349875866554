#pragma once
// The seam between the tracker driver and the OS: enumerate HID devices with their
// report descriptors, open one, exchange reports. hidapi (hidraw) implements it for
// real devices; tests put a scripted device behind it.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "foveal/core/error.hpp"

namespace foveal::hid {

struct HidDeviceEntry {
  std::string path;  ///< e.g. /dev/hidraw0
  std::uint16_t vendor_id = 0, product_id = 0;
  std::string manufacturer, product, serial;
  std::vector<std::uint8_t> descriptor;  ///< the raw report descriptor
};

class HidDevice {
 public:
  virtual ~HidDevice() = default;
  /// Reads the feature report `id` (the reply starts with the ID byte when IDs are used).
  virtual Result<std::vector<std::uint8_t>> get_feature(std::uint8_t id, std::size_t length) = 0;
  virtual Status send_feature(std::span<const std::uint8_t> report) = 0;
  /// Waits at most timeout_ms for one input report; 0 bytes = timeout. An ErrorKind::device
  /// error means the device is gone.
  virtual Result<std::size_t> read(std::span<std::uint8_t> buffer, int timeout_ms) = 0;
};

class HidBackend {
 public:
  virtual ~HidBackend() = default;
  /// Every HID device present, once each. Devices whose descriptor cannot be read are
  /// listed with an empty one.
  virtual Result<std::vector<HidDeviceEntry>> enumerate() = 0;
  virtual Result<std::unique_ptr<HidDevice>> open(const std::string& path) = 0;
};

/// hidapi with its hidraw backend; descriptors come from sysfs.
std::shared_ptr<HidBackend> make_hidapi_backend();

}  // namespace foveal::hid

#pragma once
// Lists the PlayStation VR2 headsets on the USB bus (for `foveal devices`).
#include <cstdint>
#include <string>
#include <vector>

#include "foveal/core/error.hpp"

namespace foveal::usb {

struct UsbDeviceEntry {
  std::string path;  ///< usb:BUS:ADDRESS
  std::uint16_t vendor_id = 0, product_id = 0;
  std::string name;
};

Result<std::vector<UsbDeviceEntry>> find_psvr2_devices();

}  // namespace foveal::usb

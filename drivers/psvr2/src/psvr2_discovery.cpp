#include "foveal/drivers/psvr2/psvr2_discovery.hpp"

#include <libusb-1.0/libusb.h>

#include "foveal/drivers/psvr2/psvr2_gaze_packet.hpp"

namespace foveal::usb {

Result<std::vector<UsbDeviceEntry>> find_psvr2_devices() {
  libusb_context* ctx = nullptr;
  if (int rc = libusb_init(&ctx); rc != 0) return Error{ErrorKind::device, std::string("libusb_init: ") + libusb_strerror(rc)};
  libusb_device** list = nullptr;
  const ssize_t n = libusb_get_device_list(ctx, &list);
  std::vector<UsbDeviceEntry> out;
  for (ssize_t i = 0; i < n; ++i) {
    libusb_device_descriptor d{};
    if (libusb_get_device_descriptor(list[i], &d) != 0) continue;
    if (d.idVendor != kPsvr2Vendor || d.idProduct != kPsvr2Product) continue;
    out.push_back({"usb:" + std::to_string(libusb_get_bus_number(list[i])) + ":" +
                       std::to_string(libusb_get_device_address(list[i])),
                   d.idVendor, d.idProduct, "PlayStation VR2 gaze"});
  }
  if (list) libusb_free_device_list(list, 1);
  libusb_exit(ctx);
  if (n < 0) return Error{ErrorKind::device, std::string("libusb: listing devices: ") + libusb_strerror(static_cast<int>(n))};
  return out;
}

}  // namespace foveal::usb

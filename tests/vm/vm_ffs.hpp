#pragma once
// FunctionFS, the device side of the emulated USB devices (vm_psvr2.cpp, vm_vive.cpp):
// a function's descriptors (interfaces with their endpoints, full and high speed) and
// the ep0 loop that answers the host's control requests.
#include <fcntl.h>
#include <linux/usb/ch9.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "foveal/core/clock.hpp"

namespace foveal::vmtest::ffs {

struct Endpoint {
  bool in = true;
  std::uint8_t type = USB_ENDPOINT_XFER_BULK;
  std::uint16_t fs_packet = 64, hs_packet = 512;
  std::uint8_t fs_interval = 0, hs_interval = 0;  ///< interrupt endpoints: frames / 2^(n-1) microframes
};

struct Interface {
  std::uint8_t number = 0, alt = 0, cls = USB_CLASS_VENDOR_SPEC;
  /// Written right after the interface descriptor (a HID class descriptor).
  std::vector<std::uint8_t> class_descriptor;
  std::vector<Endpoint> endpoints;
};

/// FunctionFS v2 descriptors for full and high speed. Endpoints are numbered 1, 2, ...
/// in the order listed, which is also the order of the files ep1, ep2, ... (the UDC
/// picks the addresses the host sees).
std::vector<std::uint8_t> descriptors(const std::vector<Interface>& interfaces);
/// One string (US English) for the interfaces' iInterface.
std::vector<std::uint8_t> strings(const std::string& name);

/// What the ep0 loop tells the function.
struct Handlers {
  /// An IN request: the data to send (cut to wLength), or nullopt to stall.
  std::function<std::optional<std::vector<std::uint8_t>>(const usb_ctrlrequest&)> in;
  /// An OUT request with its data stage (already acknowledged).
  std::function<void(const usb_ctrlrequest&, const std::vector<std::uint8_t>&)> out;
  /// FUNCTIONFS_ENABLE (true) and DISABLE (false): the host configured the device, or
  /// it went away.
  std::function<void(bool)> enabled;
};

/// Opens DIR/ep0 and writes the descriptors and strings; -1 after printing why not.
int open_ep0(const std::string& dir, const std::vector<Interface>& interfaces, const std::string& name);
/// Serves ep0 until `stop`.
void serve_ep0(int ep0, const std::atomic<bool>& stop, const Handlers& h);

/// Calls `make(t, fd)` at t = now + period, + 2 periods, ... on endpoint file `file`
/// while `enabled` (the host configured the device) until `stop`. A write blocks while
/// the host does not read; after such a stall, with `max_step` 0 the next t is now
/// once 50 ms behind (a sensor skipping what was not taken), else t advances by up to
/// `max_step` a call until it is now again: no gap in the device's time longer than
/// `max_step` (the emulation's stalls are the emulator's, not the headset's, which
/// would go on sampling; a fusion takes a long gap for a lost device). `written` counts
/// the calls that wrote.
template <class Make>
void stream(const std::atomic<bool>& stop, const std::string& file, const std::atomic<bool>& enabled, TimeNs period,
            TimeNs max_step, std::atomic<std::uint64_t>& written, Make make) {
  const int fd = ::open(file.c_str(), O_RDWR);
  TimeNs next = monotonic_now_ns();
  while (fd >= 0 && !stop.load()) {
    const TimeNs now = monotonic_now_ns();
    if (max_step > 0 && now > next + period) next = std::min(now, next + max_step);
    else next += period;
    sleep_until_ns(next);
    if (!enabled.load()) {
      next = monotonic_now_ns();
      continue;
    }
    if (make(next, fd)) written.fetch_add(1);
    if (max_step == 0 && monotonic_now_ns() - next > 50 * kNsPerMs) next = monotonic_now_ns();
  }
}

/// Writes all of `data` to an endpoint file (blocks while the host does not read);
/// false when the endpoint is gone (unplugged, disabled).
bool write_all(int fd, const std::vector<std::uint8_t>& data);

}  // namespace foveal::vmtest::ffs

#pragma once
// foveal_vm_guest: the programs that run inside the QEMU guest (tests/vm/init.sh).
// Each check prints one line "VMTEST <name> PASS|FAIL <details>" on the serial
// console; run_vm_tests.sh on the host reads them.
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "foveal/core/clock.hpp"

namespace foveal::vmtest {

inline bool verdict(const char* name, bool pass, const std::string& details) {
  std::printf("VMTEST %s %s %s\n", name, pass ? "PASS" : "FAIL", details.c_str());
  std::fflush(stdout);
  return pass;
}

/// Open file descriptors of this process.
int count_open_fds();

/// Polls `pred` every `period_ns` until it holds (true) or `timeout_ns` passed (false).
template <class Pred>
bool wait_for(Pred pred, TimeNs timeout_ns, TimeNs period_ns = kNsPerMs) {
  const TimeNs until = monotonic_now_ns() + timeout_ns;
  while (!pred()) {
    if (monotonic_now_ns() > until) return false;
    sleep_until_ns(monotonic_now_ns() + period_ns);
  }
  return true;
}

/// Starts `args` as a child with stdout and stderr in `log`; -1 if it cannot start.
int spawn_logged(const std::vector<std::string>& args, const std::string& log);
/// The child has exited (its wait status in `status`); does not block.
bool exited(int pid, int& status);

/// Writes a gadget's UDC file: the controller's name plugs the device in, "" unplugs it.
bool write_udc(const std::string& file, const std::string& value);
/// A hidraw device exists (sysfs).
bool hidraw_present();
/// A USB device with this VID:PID exists (sysfs).
bool usb_device_present(std::uint16_t vendor, std::uint16_t product);

int run_feed(const std::string& node);
int run_probe(int min_reports, double timeout_s);
int run_replug(const std::string& udc_file, const std::string& udc_name, int cycles);
int run_uhid();
int run_verify_log(const std::string& path, int min_samples, const std::string& name);
/// `pose`: with the head-tracking interfaces (SLAM, status with IMU records).
int run_psvr2_gadget(const std::string& ffs_dir, bool pose);
/// The Vive-class headset's IMU device (vm_vive.cpp) on the FunctionFS instance at `ffs_dir`.
int run_vive_gadget(const std::string& ffs_dir);
int run_psvr2_probe(int min_samples, double timeout_s);
int run_hex2bin(const std::string& in, const std::string& out);
/// foveald on a live source: `kind` hid or psvr2, the gadget plugged in, out and back
/// through `udc_file`, `foveald` (its arguments) started with --out and --control added.
int run_live(const std::string& kind, const std::string& udc_file, const std::string& udc_name, const std::string& out,
             std::vector<std::string> foveald);

/// foveald following an emulated headset's head (vm_hmd.cpp): `kind` psvr2 or vive.
int run_hmd(const std::string& kind, const std::string& udc_file, const std::string& udc_name, const std::string& out,
            std::vector<std::string> foveald);
/// The plugged-in emulated headset through libusb / hidraw directly (vm_hmd_probe.cpp).
int run_hmd_probe(const std::string& kind);
/// The emulated headsets' bytes through foveal's parsers, on the host (vm_hmd_selftest.cpp).
int run_hmd_selftest();

}  // namespace foveal::vmtest

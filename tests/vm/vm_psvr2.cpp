// vm psvr2 (b): an emulated PlayStation VR2. The device side is a FunctionFS gadget
// (054c:0cde, vendor interfaces, a bulk IN endpoint on interface 5) writing gaze
// records at 120 Hz; the host side is the libusb driver, which must enable the stream
// and decode every record as the pattern says. With --pose the gadget also has the
// head-tracking interfaces (psvr2_pose_pattern.hpp): SLAM poses on interface 3 and
// status transfers with IMU records on interface 7, both streaming while configured.
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <optional>
#include <cstring>
#include <thread>
#include <vector>

#include "foveal/drivers/psvr2/psvr2_source.hpp"
#include "psvr2_pattern.hpp"
#include "psvr2_pose_pattern.hpp"
#include "vm_ffs.hpp"
#include "vm_guest.hpp"

namespace foveal::vmtest {
namespace {

std::atomic<bool> g_stop{false};
void on_term(int) { g_stop.store(true); }


/// Interfaces 0..5 (gaze on 5) or, with the pose interfaces, 0..10 as the headset has
/// them (Monado's driver claims 3, 5, 6, 7, 8, 9, 10): SLAM bulk IN on 3, gaze on 5,
/// status interrupt IN on 7. The status interface is streamed in alternate setting 1,
/// and FunctionFS (Linux 6.1) has no get_alt, so it stalls SET_INTERFACE with a
/// non-zero setting; the interface is therefore described with alternate setting 1
/// alone, which the host's usb_set_interface() accepts after the stall (an interface
/// with one setting). Endpoint files: ep1 SLAM, ep2 gaze, ep3 status (ep1 gaze alone).
std::vector<ffs::Interface> psvr2_interfaces(bool pose) {
  std::vector<ffs::Interface> out;
  for (std::uint8_t i = 0; i < (pose ? 11 : 6); ++i) {
    ffs::Interface itf;
    itf.number = i;
    if (i == 5) itf.endpoints.push_back({});
    if (pose && i == usb::psvr2::kSlamInterface) itf.endpoints.push_back({});
    if (pose && i == usb::psvr2::kStatusInterface) {
      itf.alt = 1;
      itf.endpoints.push_back({true, USB_ENDPOINT_XFER_INT, 64, 1024, 1, 1});
    }
    out.push_back(itf);
  }
  return out;
}

}  // namespace

int run_psvr2_gadget(const std::string& dir, bool pose) {
  const int ep0 = ffs::open_ep0(dir, psvr2_interfaces(pose), "gaze");
  if (ep0 < 0) return 1;
  std::signal(SIGTERM, on_term);
  std::atomic<bool> configured{false};
  std::atomic<std::uint64_t> gaze_written{0}, slam_written{0}, status_written{0};
  std::vector<std::thread> writers;
  const std::string ep = dir + "/ep";
  writers.emplace_back([&] {
    // Record k is the one of the k-th period since the start: the count goes on while
    // nobody reads, as a sensor's would.
    constexpr TimeNs period = 8'333'000;
    const TimeNs t0 = monotonic_now_ns();
    ffs::stream(g_stop, ep + (pose ? "2" : "1"), configured, period, 0, gaze_written, [&](TimeNs t, int fd) {
      return ffs::write_all(fd, psvr2_record(static_cast<std::uint64_t>((t - t0) / period)));
    });
  });
  if (pose) {
    writers.emplace_back([&] {
      ffs::stream(g_stop, ep + "1", configured, kPsvr2SlamPeriodNs, 0, slam_written, [](TimeNs t, int fd) {
        // A record fills a high-speed packet: a zero-length packet ends the transfer.
        return ffs::write_all(fd, psvr2_slam_record(t)) && ::write(fd, nullptr, 0) == 0;
      });
    });
    writers.emplace_back([&] {
      constexpr TimeNs batch = kPsvr2ImuPeriodNs * kPsvr2ImuPerTransfer;
      ffs::stream(g_stop, ep + "3", configured, batch, 0, status_written, [](TimeNs t, int fd) {
        return ffs::write_all(fd, psvr2_status_transfer(t - batch + kPsvr2ImuPeriodNs, kPsvr2ImuPerTransfer));
      });
    });
  }
  ffs::Handlers h;
  h.enabled = [&](bool on) { configured = on; };
  h.in = [](const usb_ctrlrequest& c) { return std::vector<std::uint8_t>(c.wLength, 0); };  // nothing to report
  h.out = [&](const usb_ctrlrequest& c, const std::vector<std::uint8_t>& data) {
    const std::uint8_t d0 = data.empty() ? 0 : data[0], d1 = data.size() > 1 ? data[1] : 0;
    std::printf("psvr2-gadget: host request type=%02x req=%02x value=%04x index=%u data=%02x %02x (%zu bytes)\n",
                c.bRequestType, c.bRequest, c.wValue, c.wIndex, d0, d1, data.size());
    std::fflush(stdout);
  };
  ffs::serve_ep0(ep0, g_stop, h);
  std::printf("psvr2-gadget: %llu gaze records, %llu SLAM records, %llu status transfers written\n",
              static_cast<unsigned long long>(gaze_written.load()), static_cast<unsigned long long>(slam_written.load()),
              static_cast<unsigned long long>(status_written.load()));
  std::fflush(stdout);
  _exit(0);  // the writers may be blocked in bulk writes nobody reads any more
}

int run_psvr2_probe(int min_samples, double timeout_s) {
  usb::Psvr2Source src;
  if (Status s = src.open(); !s) return verdict("psvr2_read", false, "open: " + s.error().message) ? 0 : 1;
  if (Status s = src.start(); !s) return verdict("psvr2_read", false, "start: " + s.error().message) ? 0 : 1;
  std::uint64_t samples = 0, mismatches = 0, blinks = 0;
  std::optional<std::uint64_t> k;
  TimeNs last_t = 0;
  std::string problem;
  const TimeNs t0 = monotonic_now_ns(), deadline = t0 + static_cast<TimeNs>(timeout_s * 1e9);
  while (samples < static_cast<std::uint64_t>(min_samples) && monotonic_now_ns() < deadline) {
    const ReadResult r = src.next(std::chrono::milliseconds(200));
    if (r.status == ReadStatus::timeout) continue;
    if (r.status != ReadStatus::sample) {
      problem = "read stopped: " + r.error.message;
      break;
    }
    ++samples;
    const EyeSample& left = r.sample.eyes[0];
    const auto code = static_cast<std::uint64_t>(std::lround((left.pupil_mm - 2.0f) / 0.001f));
    std::uint64_t c = k ? *k + 1 : 0;
    while (c % 1000 != code % 1000) ++c;
    k = c;
    bool ok = r.sample.t_ns > last_t && left.valid == kValidAll && r.sample.eyes[1].valid == kValidAll &&
              std::abs(left.pupil_mm - psvr2_pupil(c)) < 1e-6f &&
              left.openness == (psvr2_blink(c) ? 0.0f : 1.0f) && left.origin_mm.x == -32.0f;
    last_t = r.sample.t_ns;
    blinks += psvr2_blink(c) ? 1 : 0;
    for (int e = 0; e < 2; ++e) {
      const glm::dvec3 d = psvr2_direction(c, e);
      const glm::dvec3 want{-d.x, d.y, -d.z};  // headset frame -> head frame, written out
      ok = ok && glm::length(glm::dvec3(r.sample.eyes[static_cast<std::size_t>(e)].direction) - want) < 1e-5;
    }
    if (!ok) ++mismatches;
  }
  const double secs = static_cast<double>(monotonic_now_ns() - t0) / 1e9;
  char details[400];
  std::snprintf(details, sizeof details,
                "samples=%llu in %.1f s mismatches=%llu blinks=%llu malformed=%llu endpoint=0x%02x path=%s %s",
                static_cast<unsigned long long>(samples), secs, static_cast<unsigned long long>(mismatches),
                static_cast<unsigned long long>(blinks), static_cast<unsigned long long>(src.counters().malformed),
                src.endpoint(), src.info().path.c_str(), problem.c_str());
  const bool pass = problem.empty() && samples >= static_cast<std::uint64_t>(min_samples) && mismatches == 0 &&
                    src.counters().malformed == 0 && blinks > 0;
  src.close();
  return verdict("psvr2_read", pass, details) ? 0 : 1;
}

}  // namespace foveal::vmtest

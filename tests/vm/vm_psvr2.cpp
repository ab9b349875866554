// vm psvr2 (b): an emulated PlayStation VR2 gaze interface. The device side is a
// FunctionFS gadget (054c:0cde, six vendor interfaces, a bulk IN endpoint on
// interface 5) writing gaze records at 120 Hz; the host side is the libusb driver,
// which must enable the stream and decode every record as the pattern says.
#include <fcntl.h>
#include <linux/usb/functionfs.h>
#include <poll.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <optional>
#include <cstring>
#include <thread>
#include <vector>

#include "foveal/drivers/usb/psvr2_source.hpp"
#include "psvr2_pattern.hpp"
#include "vm_guest.hpp"

namespace foveal::vmtest {
namespace {

std::atomic<bool> g_stop{false};
void on_term(int) { g_stop.store(true); }

template <class T>
void put(std::vector<std::uint8_t>& out, const T& v) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
  out.insert(out.end(), p, p + sizeof v);
}

/// FunctionFS v2 descriptors: interfaces 0..4 without endpoints, interface 5 with one
/// bulk IN endpoint, for full and high speed.
std::vector<std::uint8_t> ffs_descriptors() {
  std::vector<std::uint8_t> speed;
  for (std::uint8_t i = 0; i < 6; ++i) {
    usb_interface_descriptor itf{};
    itf.bLength = USB_DT_INTERFACE_SIZE;
    itf.bDescriptorType = USB_DT_INTERFACE;
    itf.bInterfaceNumber = i;
    itf.bNumEndpoints = i == 5 ? 1 : 0;
    itf.bInterfaceClass = USB_CLASS_VENDOR_SPEC;
    itf.iInterface = 1;
    put(speed, itf);
  }
  auto with_ep = [&](std::uint16_t max_packet) {
    std::vector<std::uint8_t> d = speed;
    usb_endpoint_descriptor_no_audio ep{};
    ep.bLength = USB_DT_ENDPOINT_SIZE;
    ep.bDescriptorType = USB_DT_ENDPOINT;
    ep.bEndpointAddress = 1 | USB_DIR_IN;
    ep.bmAttributes = USB_ENDPOINT_XFER_BULK;
    ep.wMaxPacketSize = max_packet;
    put(d, ep);
    return d;
  };
  const auto fs = with_ep(64), hs = with_ep(512);
  std::vector<std::uint8_t> out;
  usb_functionfs_descs_head_v2 head{};
  head.magic = FUNCTIONFS_DESCRIPTORS_MAGIC_V2;
  head.flags = FUNCTIONFS_HAS_FS_DESC | FUNCTIONFS_HAS_HS_DESC;
  const std::uint32_t count = 7;
  head.length = static_cast<std::uint32_t>(sizeof head + 2 * sizeof count + fs.size() + hs.size());
  put(out, head);
  put(out, count);
  put(out, count);
  out.insert(out.end(), fs.begin(), fs.end());
  out.insert(out.end(), hs.begin(), hs.end());
  return out;
}

std::vector<std::uint8_t> ffs_strings() {
  const char name[] = "gaze";
  std::vector<std::uint8_t> out;
  usb_functionfs_strings_head head{};
  head.magic = FUNCTIONFS_STRINGS_MAGIC;
  head.str_count = 1;
  head.lang_count = 1;
  head.length = static_cast<std::uint32_t>(sizeof head + 2 + sizeof name);
  put(out, head);
  const std::uint16_t lang = 0x0409;
  put(out, lang);
  out.insert(out.end(), name, name + sizeof name);
  return out;
}

}  // namespace

int run_psvr2_gadget(const std::string& dir) {
  const int ep0 = ::open((dir + "/ep0").c_str(), O_RDWR);
  if (ep0 < 0) {
    std::printf("psvr2-gadget: cannot open %s/ep0\n", dir.c_str());
    return 1;
  }
  const auto descs = ffs_descriptors(), strings = ffs_strings();
  if (::write(ep0, descs.data(), descs.size()) < 0 || ::write(ep0, strings.data(), strings.size()) < 0) {
    std::printf("psvr2-gadget: FunctionFS refused the descriptors: %s\n", std::strerror(errno));
    return 1;
  }
  std::signal(SIGTERM, on_term);
  std::atomic<bool> enabled{false};
  std::atomic<std::uint64_t> written{0};
  std::thread writer([&] {
    const int ep1 = ::open((dir + "/ep1").c_str(), O_RDWR);
    TimeNs next = monotonic_now_ns();
    for (std::uint64_t k = 0; ep1 >= 0 && !g_stop.load(); ++k) {
      next += 8'333'000;
      sleep_until_ns(next);
      if (!enabled.load()) {
        next = monotonic_now_ns();  // no backlog to catch up on once enabled
        continue;
      }
      const auto rec = psvr2_record(k);
      if (::write(ep1, rec.data(), rec.size()) == static_cast<ssize_t>(rec.size())) written.fetch_add(1);
      // A write blocks while the host does not read: go on from now, as a sensor would,
      // instead of bursting through the missed periods.
      if (monotonic_now_ns() - next > 50 * kNsPerMs) next = monotonic_now_ns();
    }
  });
  while (!g_stop.load()) {
    pollfd p{ep0, POLLIN, 0};
    if (::poll(&p, 1, 100) <= 0) continue;
    usb_functionfs_event ev[4];
    const ssize_t n = ::read(ep0, ev, sizeof ev);
    for (ssize_t i = 0; n > 0 && i < n / static_cast<ssize_t>(sizeof ev[0]); ++i) {
      if (ev[i].type == FUNCTIONFS_ENABLE) enabled.store(true);
      if (ev[i].type == FUNCTIONFS_DISABLE) enabled.store(false);
      if (ev[i].type != FUNCTIONFS_SETUP) continue;
      const usb_ctrlrequest& c = ev[i].u.setup;
      std::uint8_t data[64] = {};
      const std::size_t len = std::min<std::size_t>(c.wLength, sizeof data);
      if (c.bRequestType & USB_DIR_IN) {
        (void)::write(ep0, data, len);  // nothing to report
      } else {
        const ssize_t got = ::read(ep0, data, len);  // the data stage; also acknowledges it
        std::printf("psvr2-gadget: host request type=%02x req=%02x value=%04x index=%u data=%02x %02x (%zd bytes)\n",
                    c.bRequestType, c.bRequest, c.wValue, c.wIndex, data[0], data[1], got);
        std::fflush(stdout);
      }
    }
  }
  std::printf("psvr2-gadget: %llu records written\n", static_cast<unsigned long long>(written.load()));
  std::fflush(stdout);
  _exit(0);  // the writer may be blocked in a bulk write nobody reads any more
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

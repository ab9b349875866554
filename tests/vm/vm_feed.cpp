// vm feed: the emulated tracker's firmware. Writes Tracking Data reports at 120 Hz (and
// a Tracker Status input report every half second) into the HID gadget's /dev/hidgN,
// and logs the Mode Requests the host sends (they arrive on the same node).
#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <ctime>

#include "feeder_pattern.hpp"
#include "vm_guest.hpp"

namespace foveal::vmtest {
namespace {

std::atomic<bool> g_stop{false};
void on_term(int) { g_stop.store(true); }

}  // namespace

int run_feed(const std::string& node) {
  const int fd = ::open(node.c_str(), O_RDWR | O_NONBLOCK);
  if (fd < 0) {
    std::printf("feed: cannot open %s\n", node.c_str());
    return 1;
  }
  std::signal(SIGTERM, on_term);
  std::uint64_t written = 0, dropped = 0, modes = 0;
  timespec next{};
  ::clock_gettime(CLOCK_MONOTONIC, &next);
  for (std::uint64_t k = 0; !g_stop.load(); ++k) {
    // Not read by the host while unplugged or closed: such reports are dropped, and k
    // still advances, as a real tracker's clock would.
    const auto report = test::hutrr74::tracking_report(pattern(k));
    if (::write(fd, report.data(), report.size()) == static_cast<ssize_t>(report.size())) ++written;
    else ++dropped;
    if (k % 60 == 0) {
      // One report in flight at a time on the gadget: retry until the host took the last one.
      const auto status = test::hutrr74::status_report(1, 120);
      for (int attempt = 0; attempt < 4; ++attempt) {
        if (::write(fd, status.data(), status.size()) == static_cast<ssize_t>(status.size())) break;
        const timespec pause{0, 1'000'000};
        ::nanosleep(&pause, nullptr);
      }
    }
    pollfd p{fd, POLLIN, 0};
    while (::poll(&p, 1, 0) > 0 && (p.revents & POLLIN)) {
      std::uint8_t buf[64];
      const ssize_t n = ::read(fd, buf, sizeof buf);
      if (n <= 0) break;
      ++modes;
      std::printf("feed: host request %zd bytes: %02x %02x\n", n, buf[0], n > 1 ? buf[1] : 0);
    }
    next.tv_nsec += static_cast<long>(kPeriodUs * 1000);
    while (next.tv_nsec >= 1'000'000'000) {
      next.tv_nsec -= 1'000'000'000;
      ++next.tv_sec;
    }
    ::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
  }
  std::printf("feed: %llu reports written, %llu dropped, %llu host requests\n", static_cast<unsigned long long>(written),
              static_cast<unsigned long long>(dropped), static_cast<unsigned long long>(modes));
  ::close(fd);
  return 0;
}

}  // namespace foveal::vmtest

// vm replug (c): the runtime's gaze thread (GazeLoop) on the hidapi driver while the
// gadget is unplugged and plugged back (UDC file) again and again: every disconnect is
// seen, every replug resumes, and the open file descriptors stay the same. How fast it
// resumes is a figure this prints (the backoff's 400 ms cap bounds it on a quiet machine);
// the waits are for events, their limits (30 s) only hang guards.
#include <algorithm>
#include <atomic>

#include "feeder_pattern.hpp"
#include "foveal/drivers/hid/hid_tracker_source.hpp"
#include "foveal/runtime/gaze_loop.hpp"
#include "vm_guest.hpp"

namespace foveal::vmtest {

int run_replug(const std::string& udc_file, const std::string& udc_name, int cycles) {
  hid::HidTrackerOptions opts;
  opts.log = [](const std::string&) {};  // disconnects are expected here
  hid::HidTrackerSource src(opts);
  if (Status s = src.open(); !s || !src.start()) return verdict("gadget_replug", false, "open/start failed") ? 0 : 1;
  std::atomic<TimeNs> last_arrival{0};
  std::atomic<std::uint64_t> samples{0};
  GazeLoop loop(
      src, [](const GazeSample& s) { FoveaFrame f; f.t_ns = s.t_ns; return f; },
      [&](const GazeSample&, const FoveaFrame&) {
        last_arrival.store(monotonic_now_ns());
        samples.fetch_add(1);
      });
  loop.start();
  std::string problem;
  int recovered = 0, fd_changes = 0;
  TimeNs max_recovery = 0, sum_recovery = 0, max_from_bind = 0;
  int baseline = -1;
  constexpr TimeNs kHangGuard = 30 * kNsPerSec;
  if (!wait_for([&] { return samples.load() > 10; }, kHangGuard)) problem = "no samples before the first unplug";
  else baseline = count_open_fds();
  for (int c = 1; c <= cycles && problem.empty(); ++c) {
    if (!write_udc(udc_file, "")) {
      problem = "cannot write " + udc_file;
      break;
    }
    // GazeLoop publishes its counters once it is back, so the unplug is seen here as the
    // hidraw node going away and the samples stopping; the counters are checked at the end.
    if (!wait_for([&] { return !hidraw_present() && monotonic_now_ns() - last_arrival.load() > 100 * kNsPerMs; },
                  kHangGuard)) {
      problem = "cycle " + std::to_string(c) + ": the device did not go away";
      break;
    }
    const TimeNs t_plug = monotonic_now_ns();
    if (!write_udc(udc_file, udc_name)) {
      problem = "cannot bind " + udc_name;
      break;
    }
    // The device is back when its hidraw node is (USB enumeration on dummy_hcd comes
    // first and is the kernel's time, not the driver's).
    TimeNs t_back = 0;
    const bool resumed = wait_for(
        [&] {
          if (t_back == 0 && hidraw_present()) t_back = monotonic_now_ns();
          return last_arrival.load() > t_plug;
        },
        kHangGuard);
    if (!resumed) {
      problem = "cycle " + std::to_string(c) + ": no samples within 30 s of the replug";
      break;
    }
    if (t_back == 0) t_back = t_plug;
    const TimeNs rec = last_arrival.load() - t_back;
    max_recovery = std::max(max_recovery, rec);
    sum_recovery += rec;
    max_from_bind = std::max(max_from_bind, last_arrival.load() - t_plug);
    ++recovered;
    if (count_open_fds() != baseline) ++fd_changes;
  }
  loop.stop();
  const GazeLoopStats st = loop.stats();
  char details[600];
  std::snprintf(details, sizeof details,
                "cycles=%d recovered=%d disconnects=%llu reconnects=%llu resume_ms_after_node(max=%.0f mean=%.0f) resume_ms_after_bind(max=%.0f) "
                "fds=%d fd_changes=%d samples=%llu %s",
                cycles, recovered, static_cast<unsigned long long>(st.disconnects),
                static_cast<unsigned long long>(st.reconnects), static_cast<double>(max_recovery) / 1e6,
                recovered ? static_cast<double>(sum_recovery) / recovered / 1e6 : 0.0,
                static_cast<double>(max_from_bind) / 1e6,
                baseline, fd_changes,
                static_cast<unsigned long long>(samples.load()), problem.c_str());
  const bool pass = problem.empty() && recovered == cycles && fd_changes == 0 &&
                    st.reconnects == static_cast<std::uint64_t>(cycles) &&
                    st.disconnects == static_cast<std::uint64_t>(cycles);
  return verdict("gadget_replug", pass, details) ? 0 : 1;
}

}  // namespace foveal::vmtest

// vm probe (a): the hidapi driver reads the USB gadget tracker: >= N reports, every
// decoded value and direction checked against what the feeder sent.
#include <cmath>

#include "feeder_pattern.hpp"
#include "foveal/drivers/hid/hid_tracker_source.hpp"
#include "vm_guest.hpp"

namespace foveal::vmtest {

int run_probe(int min_reports, double timeout_s) {
  hid::HidTrackerOptions opts;
  hid::HidTrackerSource src(opts);
  if (Status s = src.open(); !s) return verdict("gadget_read", false, "open: " + s.error().message) ? 0 : 1;
  const SourceInfo info = src.info();
  if (info.vendor_id != kVendor || info.product_id != kProduct)
    return verdict("gadget_read", false, "found another tracker: " + info.path) ? 0 : 1;
  if (Status s = src.start(); !s) return verdict("gadget_read", false, "start: " + s.error().message) ? 0 : 1;
  std::uint64_t samples = 0, mismatches = 0, lost = 0, unknown_k = 0;
  std::optional<std::uint64_t> prev_k;
  double max_dir_err = 0;
  std::string first_problem;
  const TimeNs t0 = monotonic_now_ns(), deadline = t0 + static_cast<TimeNs>(timeout_s * 1e9);
  while (samples < static_cast<std::uint64_t>(min_reports) && monotonic_now_ns() < deadline) {
    const ReadResult r = src.next(std::chrono::milliseconds(200));
    if (r.status != ReadStatus::sample) {
      if (r.status == ReadStatus::timeout) continue;
      first_problem = "read stopped: " + r.error.message;
      break;
    }
    ++samples;
    const hid::TrackingData& d = src.last_tracking();
    const auto k = d.device_time_ns ? index_of(*d.device_time_ns) : std::nullopt;
    if (!k) {
      ++unknown_k;
      continue;
    }
    if (prev_k && *k > *prev_k + 1) lost += *k - *prev_k - 1;
    prev_k = k;
    const auto want = pattern(*k);
    // Exact up to the decoder's scaling (um -> 10^-4 cm -> mm), far below one micrometre.
    auto same = [](double mm, std::int32_t um) { return std::abs(mm - um / 1000.0) < 1e-9; };
    bool ok = d.gaze_valid && d.left_valid && d.right_valid && same(d.gaze_x_mm, want.gaze_x_um) &&
              same(d.gaze_y_mm, want.gaze_y_um);
    for (std::size_t a = 0; a < 3; ++a)
      ok = ok && same(d.left_eye_mm[static_cast<glm::length_t>(a)], want.left_um[a]) &&
           same(d.right_eye_mm[static_cast<glm::length_t>(a)], want.right_um[a]);
    for (int e = 0; e < 2; ++e) {
      const glm::dvec3 got = r.sample.eyes[static_cast<std::size_t>(e)].direction;
      const double err = glm::length(got - expected_direction(want, e));
      max_dir_err = std::max(max_dir_err, err);
      ok = ok && err < 1e-6 && r.sample.eyes[static_cast<std::size_t>(e)].valid == (kValidDirection | kValidOrigin);
    }
    if (!ok) {
      ++mismatches;
      if (first_problem.empty()) first_problem = "mismatch at k=" + std::to_string(*k);
    }
  }
  const double secs = static_cast<double>(monotonic_now_ns() - t0) / 1e9;
  const auto& c = src.counters();
  const double rate = src.status().sampling_frequency_hz;
  char details[512];
  std::snprintf(details, sizeof details,
                "samples=%llu in %.1f s (%.1f/s) mismatches=%llu unknown_timestamps=%llu lost=%llu malformed=%llu "
                "max_dir_err=%.2g rate_hz=%.0f path=%s %s",
                static_cast<unsigned long long>(samples), secs, static_cast<double>(samples) / secs,
                static_cast<unsigned long long>(mismatches), static_cast<unsigned long long>(unknown_k),
                static_cast<unsigned long long>(lost), static_cast<unsigned long long>(c.malformed), max_dir_err, rate,
                info.path.c_str(), first_problem.c_str());
  const bool pass = samples >= static_cast<std::uint64_t>(min_reports) && mismatches == 0 && unknown_k == 0 &&
                    c.malformed == 0 && rate == 120;
  src.close();
  return verdict("gadget_read", pass, details) ? 0 : 1;
}

}  // namespace foveal::vmtest

// vm verify-log (e): a log written by `foveal record` from the emulated tracker,
// replayed through the replay driver, holds the samples the feeder sent: each one
// matches the feeder's pattern for some report k, with k increasing.
#include <cmath>

#include <glm/geometric.hpp>

#include "feeder_pattern.hpp"
#include "foveal/drivers/replay_source.hpp"
#include "vm_guest.hpp"

namespace foveal::vmtest {
namespace {

bool matches(const GazeSample& s, std::uint64_t k) {
  const auto want = pattern(k);
  for (int e = 0; e < 2; ++e) {
    const glm::dvec3 got = s.eyes[static_cast<std::size_t>(e)].direction;
    if (glm::length(got - expected_direction(want, e)) > 1e-6) return false;
  }
  return true;
}

}  // namespace

int run_verify_log(const std::string& path, int min_samples, const std::string& name) {
  ReplayOptions o;
  o.path = path;
  o.speed = 0;
  ReplaySource src(o);
  if (Status s = src.open(); !s) return verdict(name.c_str(), false, s.error().message) ? 0 : 1;
  if (Status s = src.start(); !s) return verdict(name.c_str(), false, s.error().message) ? 0 : 1;
  std::uint64_t samples = 0, matched = 0, skipped_reports = 0;
  std::optional<std::uint64_t> k;
  for (;;) {
    const ReadResult r = src.next(std::chrono::seconds(1));
    if (r.status != ReadStatus::sample) break;
    ++samples;
    // The first sample: search the feeder's history; then the next reports only
    // (a gap of up to 10 s: unplugs)
    const std::uint64_t from = k ? *k + 1 : 0, to = k ? *k + 1200 : 200000;
    for (std::uint64_t c = from; c < to; ++c)
      if (matches(r.sample, c)) {
        if (k) skipped_reports += c - *k - 1;
        k = c;
        ++matched;
        break;
      }
  }
  char details[200];
  std::snprintf(details, sizeof details, "samples=%llu matched=%llu feeder_reports_not_in_log=%llu rate_hz=%.3f",
                static_cast<unsigned long long>(samples), static_cast<unsigned long long>(matched),
                static_cast<unsigned long long>(skipped_reports), src.header() ? src.header()->rate_hz : 0.0);
  // The rate is the device's (its status report says 120 Hz) or, when no status report
  // came in the first second, the median interval's: 8333 us, 120.005 Hz.
  const bool pass = samples >= static_cast<std::uint64_t>(min_samples) && matched == samples &&
                    src.header() && std::abs(src.header()->rate_hz - 120) < 0.01;
  return verdict(name.c_str(), pass, details) ? 0 : 1;
}

}  // namespace foveal::vmtest

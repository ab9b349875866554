#include "vm_live_follow.hpp"

#include <algorithm>
#include <cmath>

#include "feeder_pattern.hpp"
#include "foveal/core/display_model.hpp"
#include "foveal/drivers/hid/screen_gaze.hpp"
#include "foveal/runtime/gaze_pipeline.hpp"
#include "vm_guest.hpp"
#ifdef FOVEAL_VM_HAVE_USB
#include "psvr2_pattern.hpp"
#endif

namespace foveal::vmtest {

namespace {

constexpr double kPeriodNs = 8'333'333.3;  // both emulated devices send at 120 Hz

bool same_fovea(const FoveaFrame& f, const TraceRow& r) {
  for (Eye e : kEyes) {
    const auto i = static_cast<std::size_t>(e);
    const FoveaPoint& p = f.eye(e);
    if (r.state[i] != fovea_state_name(p.state) || std::abs(p.px.x - r.x[i]) > 2e-3 || std::abs(p.px.y - r.y[i]) > 2e-3)
      return false;
  }
  return true;
}

}  // namespace

Result<LiveDevice> live_device(const std::string& kind) {
  if (kind == "hid")
    return LiveDevice{hidraw_present,
                      [](std::uint64_t k) {
                        const auto p = pattern(k);
                        hid::TrackingData d;
                        d.gaze_valid = d.left_valid = d.right_valid = true;
                        d.gaze_x_mm = p.gaze_x_um / 1000.0;
                        d.gaze_y_mm = p.gaze_y_um / 1000.0;
                        d.left_eye_mm = glm::dvec3(p.left_um[0], p.left_um[1], p.left_um[2]) / 1000.0;
                        d.right_eye_mm = glm::dvec3(p.right_um[0], p.right_um[1], p.right_um[2]) / 1000.0;
                        return hid::screen_gaze_to_sample(d, hid::ScreenPlane{});
                      },
                      100000, "hid"};
#ifdef FOVEAL_VM_HAVE_USB
  if (kind == "psvr2")
    return LiveDevice{[] { return usb_device_present(kPsvr2Vendor, kPsvr2Product); },
                      [](std::uint64_t k) {
                        const auto rec = psvr2_record(k);
                        return usb::psvr2_to_sample(*usb::parse_psvr2_gaze(rec));
                      },
                      1000, "usb"};
#endif
  return bad_input("live: unknown device kind '" + kind + "' (hid, psvr2)");
}

FollowResult check_follows(const std::vector<TraceRow>& rows, TimeNs t0, const LiveDevice& dev) {
  FollowResult res;
  GazePipeline pipe(DisplayModel::vive_pro_eye(), FilterConfig{});
  std::size_t s = 0;
  while (s < rows.size() && rows[s].state[0] == "lost" && rows[s].state[1] == "lost") ++s;
  if (s == rows.size()) {
    res.problem = "no trace row with an eye in view";
    return res;
  }
  res.first_row = s;
  auto sample_at = [&](std::uint64_t k, const TraceRow& r) {
    GazeSample g = dev.sample(k);
    g.t_ns = t0 + r.rel;
    return g;
  };
  bool found = false;
  for (std::uint64_t k = 0; k < dev.period && !found; ++k) {
    pipe.reset();
    if (same_fovea(pipe.update(sample_at(k, rows[s])), rows[s])) found = true, res.k0 = k;
  }
  if (!found) {
    res.problem = "trace row " + std::to_string(s) + " is no report of the device's pattern";
    return res;
  }
  std::uint64_t k = res.k0;
  res.rows = res.matched = 1;
  // The reports after k in [1, hi], nearest first to `est`: the first whose output is the row's.
  auto advance = [&](const TraceRow& row, std::int64_t est, std::int64_t hi) {
    for (std::int64_t step = 0; step <= 2 * hi; ++step) {
      const std::int64_t d = est + (step % 2 ? (step + 1) / 2 : -(step / 2));
      if (d < 1 || d > hi) continue;
      GazePipeline trial = pipe;
      if (same_fovea(trial.update(sample_at(k + static_cast<std::uint64_t>(d), row)), row)) {
        pipe = std::move(trial);
        k += static_cast<std::uint64_t>(d);
        return d;
      }
    }
    return std::int64_t{0};
  };
  for (std::size_t j = s + 1; j < rows.size(); ++j) {
    ++res.rows;
    // The row spacing estimates how many reports on: first a few either side (the
    // device clock's offset settling, reports the host missed under load), then up to
    // 5 s of reports (a stall, a replug).
    const auto est = std::max<std::int64_t>(1, std::llround(static_cast<double>(rows[j].rel - rows[j - 1].rel) / kPeriodNs));
    std::int64_t d = advance(rows[j], est, est + 12 + est / 4);
    if (d == 0 && (d = advance(rows[j], est, 4 * est + 600)) != 0) {
      ++res.resyncs;
      res.max_resync = std::max(res.max_resync, d - est);
    }
    if (d != 0) {
      ++res.matched;
      continue;
    }
    if (res.problem.empty()) {
      char b[300];
      std::snprintf(b, sizeof b, "row %zu (t %.3f s, %.1f ms after the last): L %s (%.3f,%.3f) R %s (%.3f,%.3f) is no report after k=%llu",
                    j, static_cast<double>(rows[j].rel) / 1e9, static_cast<double>(rows[j].rel - rows[j - 1].rel) / 1e6,
                    rows[j].state[0].c_str(), rows[j].x[0], rows[j].y[0], rows[j].state[1].c_str(), rows[j].x[1],
                    rows[j].y[1], static_cast<unsigned long long>(k));
      res.problem = b;
    }
    k += static_cast<std::uint64_t>(est);
    (void)pipe.update(sample_at(k, rows[j]));
  }
  return res;
}


}  // namespace foveal::vmtest

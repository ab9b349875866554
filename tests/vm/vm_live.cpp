// vm live: foveald itself on a live source (--source hid or psvr2) against the emulated
// devices. It is started while the device is unplugged (it must say "waiting"), the
// device is plugged in, pulled out for about a second and plugged back; then foveald
// is stopped with SIGTERM and its outputs are checked:
//   live_KIND         exit 0; summary.json names the driver, the device and its state;
//                     every trace.csv row is what foveald's own pipeline makes of the
//                     samples the emulated device sent (replayed here from the device's
//                     deterministic pattern); frames.csv rows were rendered from those
//                     samples
//   live_KIND_replug  "reconnecting" while unplugged, reconnects >= 1 in summary.json,
//                     the fovea flowing again (trace.csv) within 1 s of the device's
//                     return, and frames rendered from samples after it
// Times: CLOCK_MONOTONIC everywhere. trace.csv counts from its first sample; the fovea
// shared memory's publish counter ties one of its rows to an absolute time.

#include <cmath>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "foveal/core/display_model.hpp"
#include "foveal/runtime/fovea_shm.hpp"
#include "vm_foveald.hpp"
#include "vm_guest.hpp"
#include "vm_live_files.hpp"
#include "vm_live_follow.hpp"

namespace foveal::vmtest {
namespace {

using nlohmann::json;

// How often to ask foveald's status while waiting: each request costs the emulated CPUs
// what the gaze thread needs.
constexpr TimeNs kAskEveryNs = 50 * kNsPerMs;

double ms(TimeNs ns) { return static_cast<double>(ns) / 1e6; }

}  // namespace

int run_live(const std::string& kind, const std::string& udc_file, const std::string& udc_name, const std::string& out,
             std::vector<std::string> foveald) {
  const std::string name = "live_" + kind, replug_name = name + "_replug";
  auto fail = [&](const std::string& why) {
    verdict(name.c_str(), false, why);
    verdict(replug_name.c_str(), false, "not reached: " + why);
    return 1;
  };
  auto dev = live_device(kind);
  if (!dev) return fail(dev.error().message);
  FovealdRun fd(std::move(foveald), out, "live");
  const TimeNs t_spawn = monotonic_now_ns();
  if (!fd.start()) return fail("cannot start " + fd.program());
  const json& status = fd.status();
  auto state = [&] { return fd.ask() ? str_at(status, "/source/state") : std::string("?"); };

  // 1. Started before the device is there: waiting for it.
  std::string problem;
  TimeNs t_first_frames = 0, t_unplug = 0, t_node_gone = 0, t_replug = 0, t_back = 0, t_seen = 0;
  bool saw_reconnecting = false;
  std::string state_before, waiting_for;
  FoveaShmPayload anchor{};
  if (!wait_for([&] { return !fd.alive() || fd.ask(); }, 120 * kNsPerSec, kAskEveryNs) || !fd.alive()) problem = "foveald's control socket never answered";
  if (problem.empty()) {
    // The first open is under way when the socket opens; its failure says why it waits.
    wait_for([&] { return !fd.ask() || !str_at(status, "/source/waiting_for").empty(); }, 20 * kNsPerSec, kAskEveryNs);
    state_before = str_at(status, "/source/state");
    waiting_for = str_at(status, "/source/waiting_for");
    std::printf("live: control after %.1f s: source %s (%s)\n", ms(monotonic_now_ns() - t_spawn) / 1e3,
                state_before.c_str(), waiting_for.c_str());
    // 2. Plugged in: samples flow and frames are rendered.
    if (!write_udc(udc_file, udc_name)) problem = "cannot bind " + udc_name;
  }
  if (problem.empty() &&
      !wait_for([&] {
        return !fd.alive() || (fd.ask() && u64_at(status, "/samples") >= 240 && u64_at(status, "/render/frames") >= 3);
      }, 120 * kNsPerSec, kAskEveryNs))
    problem = "no 240 samples and 3 frames within 120 s of the plug-in: " + status.dump().substr(0, 300);
  if (problem.empty() && !fd.alive()) problem = "foveald exited";
  if (problem.empty()) {
    t_first_frames = monotonic_now_ns();
    std::printf("live: streaming: %s\n", at(status, "/source").dump().c_str());
    std::fflush(stdout);
    auto shm = FoveaShm::open(default_fovea_shm_name());
    if (!shm || !shm->read(anchor) || anchor.frame == 0) problem = "no fovea in shared memory";
  }
  // 3. Unplugged for about a second, then back.
  if (problem.empty()) {
    t_unplug = monotonic_now_ns();
    if (!write_udc(udc_file, "")) problem = "cannot unbind";
    else if (!wait_for([&] { return !dev->present(); }, 5 * kNsPerSec)) problem = "the device did not go away";
    t_node_gone = monotonic_now_ns();
    saw_reconnecting = problem.empty() && wait_for([&] { return state() == "reconnecting"; }, 5 * kNsPerSec, kAskEveryNs);
    sleep_until_ns(std::max(monotonic_now_ns(), t_unplug + kNsPerSec));
  }
  if (problem.empty()) {
    t_replug = monotonic_now_ns();
    if (!write_udc(udc_file, udc_name)) problem = "cannot bind " + udc_name + " again";
    else if (!wait_for([&] { return (t_back = dev->present() ? monotonic_now_ns() : 0) != 0; }, 10 * kNsPerSec))
      problem = "the device did not come back";
  }
  if (problem.empty()) {
    auto shm = FoveaShm::open(default_fovea_shm_name());
    FoveaShmPayload p{};
    if (!shm || !wait_for([&] { return shm->read(p) && p.t_ns > t_replug; }, 10 * kNsPerSec))
      problem = "no fovea within 10 s of the replug";
    t_seen = monotonic_now_ns();
    // Then a while longer: frames rendered from samples after the replug.
    const auto frames_then = fd.ask() ? u64_at(status, "/render/frames") : 0;
    wait_for([&] {
      return !fd.alive() || (monotonic_now_ns() > t_back + 2 * kNsPerSec && fd.ask() &&
                          u64_at(status, "/render/frames") >= frames_then + 3);
    }, 60 * kNsPerSec, kAskEveryNs);
  }
  // 4. SIGTERM, then the outputs.
  const FovealdRun::Stopped stopped = fd.stop();
  if (problem.empty()) problem = stopped.problem;
  const double term_ms = stopped.term_ms;
  const int rc = stopped.rc;
  std::printf("live: foveald exit %d, %.0f ms after SIGTERM; its log:\n", rc, term_ms);
  std::fflush(stdout);
  if (std::ifstream lf(out + ".log"); lf) std::printf("%s\n", std::string(std::istreambuf_iterator<char>(lf), {}).c_str());

  const json summary = read_json(out + "/summary.json");
  const auto rows = read_trace(out + "/trace.csv");
  const auto frames = read_frames(out + "/frames.csv");
  const json src = at(summary, "/source");
  std::printf("live: summary source %s, render frames %s\n", src.dump().c_str(), at(summary, "/render/frames").dump().c_str());

  // trace.csv on the absolute clock: row frame-1 is the sample of the anchor's publish.
  TimeNs t0 = 0;
  if (anchor.frame >= 1 && anchor.frame <= rows.size()) t0 = anchor.t_ns - rows[anchor.frame - 1].rel;
  else if (problem.empty()) problem = "the shared memory's publish " + std::to_string(anchor.frame) + " is not in trace.csv";
  const FollowResult follows = check_follows(rows, t0, *dev);

  // Frames: their fovea time names a trace row, whose fovea they show.
  std::map<TimeNs, std::size_t> by_rel;
  for (std::size_t i = 0; i < rows.size(); ++i) by_rel[rows[i].rel] = i;
  const DisplayModel model = DisplayModel::vive_pro_eye();
  std::size_t live_frames = 0, frames_after = 0, frame_mismatch = 0;
  for (const FrameRow& f : frames) {
    if (f.t_ns == 0) continue;  // before the first sample: the centre
    const auto it = by_rel.find(f.t_ns - t0);
    bool ok = it != by_rel.end();
    for (int e = 0; ok && e < 2; ++e) {
      const TraceRow& r = rows[it->second];
      ok = std::abs(f.fx[e] - r.x[e] / model.eye_width) < 5e-5 && std::abs(f.fy[e] - r.y[e] / model.eye_height) < 5e-5;
    }
    if (!ok) {
      ++frame_mismatch;
      continue;
    }
    ++live_frames;
    if (f.t_ns > t_replug) ++frames_after;
  }

  // Recovery: the first sample after the replug against the device's return.
  std::size_t resume = rows.size(), before_gap = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (t0 + rows[i].rel <= t_unplug) before_gap = i + 1;
    if (t0 + rows[i].rel > t_replug) {
      resume = i;
      break;
    }
  }
  const TimeNs t_resume = resume < rows.size() ? t0 + rows[resume].rel : 0;
  const std::size_t after_gap = rows.size() - resume;

  const auto u64 = [&](const char* p) { return u64_at(summary, p); };
  const std::string dev_path = str_at(src, "/device/path");
  const bool path_ok = kind == "hid" ? dev_path.rfind("/dev/hidraw", 0) == 0 : !dev_path.empty();
  char details[1200];
  std::snprintf(details, sizeof details,
                "exit=%d term_ms=%.0f before_plug=%s samples=%llu trace_rows=%zu follows=%zu/%zu (k0=%llu from row %zu, "
                "resyncs=%zu max=%lld) "
                "frames=%zu live_frames=%zu frame_mismatches=%zu device=%s(%s) state=%s %s %s",
                rc, term_ms, state_before.c_str(), static_cast<unsigned long long>(u64("/samples")), rows.size(),
                follows.matched, follows.rows, static_cast<unsigned long long>(follows.k0), follows.first_row,
                follows.resyncs, static_cast<long long>(follows.max_resync), frames.size(), live_frames, frame_mismatch, dev_path.c_str(),
                at(src, "/device/driver").dump().c_str(), at(src, "/state").dump().c_str(), problem.c_str(),
                follows.problem.c_str());
  const bool pass = problem.empty() && rc == 0 && state_before == "waiting" && !waiting_for.empty() &&
                    at(src, "/driver") == kind && at(src, "/live") == true && at(src, "/state") == "stopped" &&
                    at(src, "/device/driver") == dev->device_driver && path_ok && u64("/samples") == rows.size() &&
                    rows.size() >= 300 && follows.problem.empty() && follows.matched + follows.first_row == rows.size() &&
                    at(summary, "/render/frames") == frames.size() && at(summary, "/render/size") == json({64, 36}) &&
                    live_frames >= 3 && frame_mismatch == 0;
  verdict(name.c_str(), pass, details);

  std::snprintf(details, sizeof details,
                "disconnects=%s reconnects=%s saw_reconnecting=%d unplugged_ms=%.0f gone_after_ms=%.0f "
                "back_after_replug_ms=%.0f resume_ms_after_device_back=%.0f resume_ms_after_replug=%.0f "
                "shm_fovea_ms_after_replug=%.0f rows_before=%zu rows_after=%zu frames_after_replug=%zu "
                "streaming_after_s=%.1f %s",
                at(src, "/disconnects").dump().c_str(), at(src, "/reconnects").dump().c_str(), saw_reconnecting ? 1 : 0,
                ms(t_replug - t_unplug), ms(t_node_gone - t_unplug), ms(t_back - t_replug), ms(t_resume - t_back),
                ms(t_resume - t_replug), ms(t_seen - t_replug), before_gap, after_gap, frames_after,
                ms(t_first_frames - t_spawn) / 1e3, problem.c_str());
  const bool replug_pass = problem.empty() && saw_reconnecting && u64_at(src, "/reconnects") >= 1 &&
                           at(src, "/reconnects") == at(src, "/disconnects") && at(summary, "/reconnects") == at(src, "/reconnects") &&
                           t_resume > t_back && t_resume - t_back < kNsPerSec && before_gap >= 240 && after_gap >= 60 &&
                           frames_after >= 3;
  verdict(replug_name.c_str(), replug_pass, details);
  return pass && replug_pass ? 0 : 1;
}

}  // namespace foveal::vmtest

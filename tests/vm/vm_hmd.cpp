// vm hmd: foveald following an emulated headset's head (--head psvr2 or --head vive)
// against the FunctionFS devices of vm_psvr2.cpp (--pose) and vm_vive.cpp. The PS VR2 is
// plugged in after foveald started (its head waits for it); the Vive before (foveald
// reads the headset's display model when it starts). The headset is pulled out for
// about a second and plugged back; then foveald is stopped with SIGTERM and its
// outputs are checked:
//   hmd_KIND         exit 0; frames.csv's head columns follow the motion script
//                    (vm_hmd_check.hpp) before the unplug and after the replug; for the
//                    Vive, foveald renders with the display model read from the headset
//                    and `foveal devices --display-model` writes that model (checked
//                    against the emulated configuration: hmd_vive_display_model)
//   hmd_KIND_replug  the head said reconnecting while unplugged and held the last pose,
//                    summary.json counts the reconnect, poses flow again after the replug
//                    and frames are rendered from them
// Times: CLOCK_MONOTONIC everywhere; the emulated motion is a function of it.
#include <signal.h>
#include <sys/wait.h>

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "psvr2_pattern.hpp"
#include "vive_pattern.hpp"
#include "vm_foveald.hpp"
#include "vm_guest.hpp"
#include "vm_hmd_check.hpp"
#include "vm_live_files.hpp"

namespace foveal::vmtest {
namespace {

using nlohmann::json;

constexpr TimeNs kAskEveryNs = 100 * kNsPerMs;  // status requests cost the emulated CPUs
constexpr TimeNs kSettleNs = 3 * kNsPerSec;     // the fused orientation converges from the first samples

double ms(TimeNs ns) { return static_cast<double>(ns) / 1e6; }

std::string file_text(const std::string& path) {
  std::ifstream f(path);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

/// `foveal devices --display-model PATH` against the plugged-in Vive; the file checked.
bool check_display_model(const std::string& path) {
  const int pid = spawn_logged({"foveal", "devices", "--display-model", path}, path + ".log");
  int st = 0;
  if (pid < 0 || !wait_for([&] { return exited(pid, st); }, 60 * kNsPerSec, 10 * kNsPerMs)) {
    if (pid > 0) ::kill(pid, SIGKILL);
    return verdict("hmd_vive_display_model", false, "foveal devices did not finish: " + file_text(path + ".log"));
  }
  const json model = read_json(path);
  const ModelCheck c = check_vive_model(model);
  const bool pass = WIFEXITED(st) && WEXITSTATUS(st) == 0 && c.pass;
  return verdict("hmd_vive_display_model", pass,
                 "exit=" + std::to_string(WIFEXITED(st) ? WEXITSTATUS(st) : -1) + " " + c.details +
                     (pass ? "" : " log: " + file_text(path + ".log").substr(0, 300)));
}

}  // namespace

int run_hmd(const std::string& kind, const std::string& udc_file, const std::string& udc_name, const std::string& out,
            std::vector<std::string> foveald) {
  const std::string name = "hmd_" + kind, replug_name = name + "_replug";
  auto fail = [&](const std::string& why) {
    verdict(name.c_str(), false, why);
    verdict(replug_name.c_str(), false, "not reached: " + why);
    return 1;
  };
  const bool vive = kind == "vive";
  if (!vive && kind != "psvr2") return fail("unknown headset '" + kind + "' (psvr2, vive)");
  auto present = [&] {
    return vive ? usb_device_present(kViveVendor, kViveProduct) : usb_device_present(kPsvr2Vendor, kPsvr2Product);
  };
  FovealdRun fd(std::move(foveald), out, "hmd");
  const json& status = fd.status();
  auto head_state = [&] { return fd.ask() ? str_at(status, "/head/state") : std::string("?"); };
  auto poses = [&] { return u64_at(status, "/head/poses"); };
  auto frames = [&] { return u64_at(status, "/render/frames"); };

  std::string problem, state_before;
  TimeNs t_plug = 0, t_unplug = 0, t_replug = 0, t_back = 0, t_resumed = 0;
  bool saw_reconnecting = false, model_ok = true;
  std::uint64_t poses_at_unplug = 0;
  const bool plugged_first = vive;
  if (plugged_first) {
    t_plug = monotonic_now_ns();
    if (!write_udc(udc_file, udc_name)) problem = "cannot bind " + udc_name;
    else if (!wait_for(present, 10 * kNsPerSec) || !wait_for(hidraw_present, 10 * kNsPerSec)) problem = "the headset did not appear";
  }
  const TimeNs t_spawn = monotonic_now_ns();
  if (problem.empty() && !fd.start()) problem = "cannot start " + fd.program();
  // 1. The PS VR2 is not there yet: the head waits for it.
  if (problem.empty() && (!wait_for([&] { return !fd.alive() || fd.ask(); }, 120 * kNsPerSec, kAskEveryNs) || !fd.alive()))
    problem = "foveald's control socket never answered";
  if (problem.empty()) {
    state_before = head_state();
    std::printf("hmd: after the start: %s\n", at(status, "/head").dump().c_str());
  }
  if (problem.empty() && !plugged_first) {
    // 2. Plugged in: poses flow, frames are rendered from them.
    t_plug = monotonic_now_ns();
    if (!write_udc(udc_file, udc_name)) problem = "cannot bind " + udc_name;
  }
  // The first frame can take many seconds in the guest (shader compilation on one slow
  // core): the checked window needs frames for 4 s after they start, not just 6 s of clock.
  TimeNs t_frames = 0;
  if (problem.empty() && !wait_for([&] {
        if (!fd.alive()) return true;
        if (!fd.ask() || poses() < 100 || frames() < 3) return false;
        const TimeNs now = monotonic_now_ns();
        if (t_frames == 0) t_frames = now;
        return now > t_plug + kSettleNs + 6 * kNsPerSec && now > t_frames + 4 * kNsPerSec;
      }, 180 * kNsPerSec, kAskEveryNs))
    problem = "no poses and frames within 180 s of the plug-in: " + status.dump().substr(0, 400);
  if (problem.empty() && !fd.alive()) problem = "foveald exited";
  if (problem.empty()) {
    std::printf("hmd: tracking: %s\n", at(status, "/head").dump().c_str());
    std::fflush(stdout);
    if (vive) model_ok = check_display_model(out + "-model.json");
  }
  // 3. Unplugged for about a second: the head holds its last pose and reconnects.
  if (problem.empty()) {
    if (fd.ask()) poses_at_unplug = poses();
    t_unplug = monotonic_now_ns();
    if (!write_udc(udc_file, "")) problem = "cannot unbind";
    else if (!wait_for([&] { return !present(); }, 5 * kNsPerSec)) problem = "the headset did not go away";
    saw_reconnecting = problem.empty() && wait_for([&] { return head_state() == "reconnecting"; }, 5 * kNsPerSec, kAskEveryNs);
    sleep_until_ns(std::max(monotonic_now_ns(), t_unplug + kNsPerSec));
  }
  if (problem.empty()) {
    t_replug = monotonic_now_ns();
    if (!write_udc(udc_file, udc_name)) problem = "cannot bind " + udc_name + " again";
    else if (!wait_for([&] { return (t_back = present() ? monotonic_now_ns() : 0) != 0; }, 10 * kNsPerSec))
      problem = "the headset did not come back";
  }
  if (problem.empty()) {
    const std::uint64_t before = poses();
    if (!wait_for([&] { return fd.ask() && poses() > before + 10; }, 30 * kNsPerSec, kAskEveryNs))
      problem = "no poses within 30 s of the replug";
    t_resumed = monotonic_now_ns();
    const std::uint64_t frames_then = frames();
    wait_for([&] {
      return !fd.alive() || (monotonic_now_ns() > t_back + kSettleNs + 6 * kNsPerSec && fd.ask() && frames() >= frames_then + 5);
    }, 120 * kNsPerSec, kAskEveryNs);
  }
  // 4. SIGTERM, then the outputs.
  if (!fd.started()) return fail(problem);
  const FovealdRun::Stopped stopped = fd.stop();
  if (problem.empty()) problem = stopped.problem;
  const int rc = stopped.rc;
  const TimeNs t_term = stopped.t_term;
  std::printf("hmd: foveald exit %d, %.0f ms after SIGTERM; its log:\n%s\n", rc, stopped.term_ms,
              file_text(out + ".log").c_str());
  const json summary = read_json(out + "/summary.json");
  const json head = at(summary, "/head");
  std::printf("hmd: summary head %s display_model %s\n", head.dump().c_str(), at(summary, "/display_model").dump().c_str());
  std::fflush(stdout);

  std::string rows_problem;
  const auto rows = read_head_rows(out + "/frames.csv", rows_problem);
  // Before the unplug and after the replug, once the orientation had time to settle.
  // (The Vive is plugged in before foveald starts: its first frames are taken at the start.)
  const std::vector<Window> windows{{std::max(t_plug, t_spawn) + kSettleNs, t_unplug}, {t_back + kSettleNs, t_term}};
  const FollowCheck follow = vive ? check_vive_rows(rows, windows) : check_psvr2_rows(rows, windows);
  std::size_t after = 0, during = 0, during_moved = 0;
  const HeadRow* held = nullptr;
  for (const HeadRow& r : rows) {
    const TimeNs t = r.pose_t_ns ? r.pose_t_ns : r.t_ns;
    if (t > t_back + kSettleNs) ++after;
    // Rendered while nothing arrived (from 200 ms after the unplug, past the 100 ms after
    // which a pose counts as held, to the replug): the same pose, held.
    if (r.t_ns > t_unplug + 200 * kNsPerMs && r.t_ns < t_replug) {
      ++during;
      if (!held) held = &r;
      if (glm::length(r.pose.position_m - held->pose.position_m) > 1e-5f ||
          std::abs(glm::dot(r.pose.orientation, held->pose.orientation)) < 1 - 1e-6f)
        ++during_moved;
    }
  }
  if (follow.bad > 0) std::printf("hmd: the frames' head poses:\n%s", describe_rows(rows).c_str());
  // The Vive's display model is named after its model number (vive_config_json).
  const std::string display = str_at(summary, "/display_model");
  const bool display_ok = !vive || display == "vive_vive_pro_mv";
  char details[1200];
  std::snprintf(details, sizeof details,
                "exit=%d before_plug=%s frames=%zu %s display_model=%s %s %s", rc, state_before.c_str(), rows.size(),
                follow.summary().c_str(), display.c_str(), rows_problem.c_str(), problem.c_str());
  const bool pass = problem.empty() && rows_problem.empty() && rc == 0 && (plugged_first || state_before == "waiting") &&
                    follow.bad == 0 &&
                    follow.checked >= 10 && display_ok && model_ok;
  verdict(name.c_str(), pass, details);

  std::snprintf(details, sizeof details,
                "saw_reconnecting=%d disconnects=%s reconnects=%s poses_at_unplug=%llu unplugged_ms=%.0f "
                "back_after_replug_ms=%.0f poses_after_ms=%.0f frames_while_unplugged=%zu (moved %zu) frames_after=%zu %s",
                saw_reconnecting ? 1 : 0, at(head, "/disconnects").dump().c_str(), at(head, "/reconnects").dump().c_str(),
                static_cast<unsigned long long>(poses_at_unplug), ms(t_replug - t_unplug), ms(t_back - t_replug),
                ms(t_resumed - t_back), during, during_moved, after, problem.c_str());
  const bool replug_pass = problem.empty() && saw_reconnecting && u64_at(head, "/reconnects") >= 1 && during >= 1 &&
                           during_moved == 0 && after >= 5;
  verdict(replug_name.c_str(), replug_pass, details);
  return pass && replug_pass ? 0 : 1;
}

}  // namespace foveal::vmtest

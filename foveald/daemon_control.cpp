// foveald's control thread: the control socket and the signals, served whatever the
// renderer or a device is doing. It reads the gaze loop's and the renderer's published
// stats and writes settings through the SeqLock; it never waits for a frame.
#include <poll.h>
#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <cstdio>
#include <set>

#include "daemon_app.hpp"
#include "daemon_output.hpp"
#include "foveal/core/json_text.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/runtime/log.hpp"
#include "process_stats.hpp"

namespace foveal::daemon {

namespace {

/// How long after SIGTERM/SIGINT the main thread may stay inside a frame before this
/// thread ends the process itself (well inside the 1 s a service manager is promised).
constexpr TimeNs kEmergencyAfterNs = 300 * kNsPerMs;
constexpr int kPollMs = 10;

nlohmann::json fovea_json(const FoveaFrame& f) {
  nlohmann::json j = {{"t_ns", f.t_ns}};
  for (Eye e : kEyes) {
    const FoveaPoint& p = f.eye(e);
    j[eye_name(e)] = {{"x_px", p.px.x}, {"y_px", p.px.y}, {"state", fovea_state_name(p.state)}, {"confidence", p.confidence}};
  }
  return j;
}

nlohmann::json error_reply(const std::string& msg) { return {{"ok", false}, {"error", msg}}; }

double ms(std::int64_t ns) { return static_cast<double>(ns) / 1e6; }

}  // namespace

void DaemonApp::control_thread(int signal_fd) {
  const auto handler = [this](const nlohmann::json& r) { return handle(r); };
  while (!control_stop_.load()) {
    if (control_) {
      control_->poll(kPollMs, handler);
    } else {
      pollfd p{signal_fd, POLLIN, 0};
      ::poll(&p, 1, kPollMs);
    }
    handle_signals(signal_fd);
    if (shm_) shm_->heartbeat();  // readers take a silent block for a dead foveald
    print_status_line();
    const TimeNs asked = stop_requested_at_.load();
    if (asked > 0 && monotonic_now_ns() - asked > kEmergencyAfterNs && claim_shutdown(control)) emergency_exit();
  }
}

void DaemonApp::handle_signals(int signal_fd) {
  signalfd_siginfo si{};
  while (signal_fd >= 0 && ::read(signal_fd, &si, sizeof si) == static_cast<ssize_t>(sizeof si)) {
    if (si.ssi_signo == SIGHUP) {
      auto p = store_.load(profile_.name);
      if (!p) log::error(p.error().message + "; keeping the last good profile");
      else if (Status s = apply_profile(*p, "reloaded"); !s) log::error(s.error().message);
    } else if (TimeNs none = 0; stop_requested_at_.compare_exchange_strong(none, monotonic_now_ns())) {
      log::info(std::string("stopping on ") + (si.ssi_signo == SIGINT ? "SIGINT" : "SIGTERM"));
    }
  }
}

nlohmann::json DaemonApp::source_json() const {
  const GazeLoopStats st = loop_ ? loop_->stats() : GazeLoopStats{};
  nlohmann::json j = {{"spec", source_text_},
                      {"driver", source_.spec.driver},
                      {"live", source_.live},
                      {"state", source_state_name(st.state)},
                      {"device", {{"driver", st.device.driver}, {"name", st.device.name}, {"path", st.device.path}}},
                      {"disconnects", st.disconnects},
                      {"reconnects", st.reconnects}};
  if (!st.waiting_for.empty()) j["waiting_for"] = st.waiting_for;
  if (source_.spec.driver == "replay") j["speed"] = o_.speed;
  return j;
}

nlohmann::json DaemonApp::status_json() const {
  const GazeLoopStats st = loop_ ? loop_->stats() : GazeLoopStats{};
  RenderSettings rs;
  (void)settings_.load(rs);
  const double up_s = static_cast<double>(monotonic_now_ns() - started_) / 1e9;
  const char* state = st.ended                               ? "ended"
                      : st.failed                            ? "failed"
                      : stopping()                           ? "stopped"
                      : (loop_ && loop_->paused())           ? "paused"
                      : st.state == SourceState::streaming   ? "running"
                                                             : source_state_name(st.state);
  return {{"ok", true},
          {"state", state},
          {"uptime_s", up_s},
          {"source", source_json()},
          {"profile", profile_.name},
          {"settings", {{"dominant_eye", rs.dominant_eye == 0 ? "left" : "right"}, {"sigma_d", rs.sigma_d},
                        {"sigma_nd", rs.sigma_nd}, {"f_x", rs.f_x < 0 ? nlohmann::json("auto") : nlohmann::json(rs.f_x)},
                        {"f_y", rs.f_y < 0 ? nlohmann::json("auto") : nlohmann::json(rs.f_y)}, {"generation", rs.generation}}},
          {"samples", st.samples},
          {"samples_skipped_paused", st.skipped},
          {"sample_rate_hz", up_s > 0 ? static_cast<double>(st.samples) / up_s : 0.0},
          {"latency_ms", {{"p50", ms(st.latency_p50_ns)}, {"p99", ms(st.latency_p99_ns)}, {"max", ms(st.latency_max_ns)}}},
          {"realtime", st.realtime},
          {"disconnects", st.disconnects},
          {"reconnects", st.reconnects},
          {"markers", markers_.pushed()},
          {"resident_mb", current_rss_mb()},
          {"render", renderer_ ? renderer_->stats_json() : nlohmann::json(nullptr)},
          {"head", head_ ? head_->json() : nlohmann::json(nullptr)},
          {"control", {{"requests", control_ ? control_->requests_served() : 0}, {"bad_requests", control_ ? control_->bad_requests() : 0}}},
          // Log lines lost because stderr did not keep up (a pipe nobody reads).
          {"log", {{"dropped_lines", log::dropped_lines()}}}};
}

nlohmann::json DaemonApp::handle(const nlohmann::json& req) {
  // ControlServer::answer has already refused a request without a string "cmd".
  const std::string cmd = req.at("cmd").get<std::string>();
  // A change's reply says which settings generation carries it; the renderer reports the
  // one it last applied as render.settings_generation.
  const auto changed = [this] {
    nlohmann::json j = status_json();
    j["applies_generation"] = settings_generation_;
    return j;
  };
  if (cmd == "status") return status_json();
  if (cmd == "fovea") {
    FoveaFrame f;
    if (!loop_ || !loop_->latest().load(f)) return error_reply("no fovea yet");
    nlohmann::json j = fovea_json(f);
    // The figures' pixel space: one eye's viewport of the display model, origin top-left.
    j["space"] = {{"eye_width", model_.eye_width}, {"eye_height", model_.eye_height}, {"origin", "top-left, y down"}};
    j["ok"] = true;
    return j;
  }
  if (cmd == "profiles") {
    auto names = store_.list();
    if (!names) return error_reply(names.error().message);
    return {{"ok", true}, {"profiles", *names}, {"active", profile_.name}};
  }
  if (cmd == "use") {
    if (!req.contains("profile") || !req["profile"].is_string()) return error_reply("use: expected \"profile\": NAME");
    auto p = store_.load(req["profile"].get<std::string>());
    if (!p) return error_reply(p.error().message);
    if (Status s = apply_profile(*p, "switched to"); !s) return error_reply(s.error().message);
    return changed();
  }
  if (cmd == "set") {
    // Validate the change as a whole profile so that bad pairs never reach a frame.
    static const std::set<std::string> kRunTimeKeys = {"dominant_eye", "sigma_d", "sigma_nd", "f_x", "f_y"};
    nlohmann::json j = profile_.to_json();
    for (auto it = req.begin(); it != req.end(); ++it) {
      if (it.key() == "cmd") continue;
      if (!kRunTimeKeys.count(it.key()))
        return error_reply("set: '" + it.key() + "' cannot be set at run time (dominant_eye, sigma_d, sigma_nd, f_x, f_y)");
      j[it.key()] = it.value();
      // Levels set by hand win over levels chosen by perception.
      if (it.key() != "dominant_eye") j["quality"] = "off";
    }
    auto p = Profile::from_json(j, profile_.name, "set");
    if (!p) return error_reply(p.error().message);
    if (Status s = apply_profile(*p, "changed"); !s) return error_reply(s.error().message);
    return changed();
  }
  if (cmd == "pause" || cmd == "resume") {
    if (loop_) loop_->set_paused(cmd == "pause");
    return status_json();
  }
  if (cmd == "mark") {
    // Stamped on arrival, on the samples' clock; the gaze thread writes it into the trace.
    const auto text = req.find("text");
    if (text == req.end() || !text->is_string()) return error_reply("mark: expected \"text\": a string");
    if (Status s = check_marker_text(text->get<std::string>()); !s) return error_reply(s.error().message);
    const TimeNs now = monotonic_now_ns();
    if (!markers_.push({now, text->get<std::string>()}))
      return error_reply("mark: " + std::to_string(cli::MarkerQueue::kMaxWaiting) +
                         " markers wait for the next sample already; refused");
    return {{"ok", true}, {"t_ns", now}, {"markers", markers_.pushed()}};
  }
  return error_reply("unknown request '" + cmd + "' (status, fovea, profiles, use, set, pause, resume, mark)");
}

void DaemonApp::print_status_line() {
  if (o_.json || !log::enabled(log::Level::info) || !::isatty(STDERR_FILENO) || !loop_) return;
  const TimeNs now = monotonic_now_ns();
  if (now - last_status_ < kNsPerSec / 4) return;
  last_status_ = now;
  const GazeLoopStats st = loop_->stats();
  FoveaFrame f;
  (void)loop_->latest().load(f);
  // Through the log's queue: a terminal stopped by ^S must not stop this thread.
  char line[256];
  std::snprintf(line, sizeof line, "\rfoveald: %s %s %llu samples  reconnects %llu  latency p99 %.3f ms  L(%4.0f,%4.0f) %-8s R(%4.0f,%4.0f) %-8s ",
                loop_->paused() ? "paused" : source_state_name(st.state), source_.spec.driver.c_str(),
                static_cast<unsigned long long>(st.samples), static_cast<unsigned long long>(st.reconnects),
                ms(st.latency_p99_ns), f.eyes[0].px.x, f.eyes[0].px.y, fovea_state_name(f.eyes[0].state),
                f.eyes[1].px.x, f.eyes[1].px.y, fovea_state_name(f.eyes[1].state));
  log::raw(line);
}

nlohmann::json DaemonApp::summary_json() const {
  nlohmann::json j = status_json();
  j.erase("ok");
  j["display_model"] = model_.name;
  j["trace"] = trace_->on() ? nlohmann::json(o_.out + "/trace.csv") : nlohmann::json(nullptr);
  // trace.csv counts from its first row: this is that row's CLOCK_MONOTONIC time, the clock
  // of the shared block and of OpenXR apps' converted times (docs/openxr.md).
  if (auto t0 = trace_->t0_ns()) j["trace_t0_ns"] = *t0;
  j["peak_rss_mb"] = peak_rss_mb();
  // The driver's own counters; the gaze thread has stopped, so reading them is safe.
  if (loop_ && loop_->finished() && source_.counters) j["source"]["counters"] = source_.counters();
  // Soak figures: resident memory and open descriptors after warm-up and at the end.
  if (warm_rss_mb_ >= 0)
    j["resources"] = {{"warm", {{"rss_mb", warm_rss_mb_.load()}, {"fds", warm_fds_.load()}}},
                      {"end", {{"rss_mb", current_rss_mb()}, {"fds", open_fds()}}},
                      {"rss_growth_mb", current_rss_mb() - warm_rss_mb_}};
  if (pacing_.count() > 0 && loop_ && loop_->finished())
    j["pacing_error_ms"] = {{"p50", ms(pacing_.percentile(0.5))}, {"p99", ms(pacing_.percentile(0.99))},
                            {"max", ms(pacing_.max())}};
  return j;
}

void DaemonApp::emergency_exit() {
  // The main thread is inside a frame (llvmpipe at 2880x1600 takes about a second) and
  // will not touch the outputs again: it parks once it sees this thread owns shutdown.
  log::info("a frame is still in flight: finishing without it");
  loop_->stop();
  head_->stop();
  int rc = cli::kExitOk;
  trace_->write_markers(markers_.take_all());
  Status s = trace_->commit();
  if (s && renderer_) s = renderer_->abandon();
  nlohmann::json summary = summary_json();
  summary["render_abandoned_frame_in_flight"] = true;
  if (s) s = write_file_atomically(o_.out + "/summary.json", json_text(summary, 2) + "\n");
  if (!s) rc = report(s.error());
  else if (o_.json) print_json(summary);
  control_.reset();  // removes the socket
  shm_.reset();      // and the shared-memory block
  std::fflush(stdout);
  log::flush(/*stall_ms=*/100);  // the last lines, unless stderr is stuck
  ::_exit(rc);  // the main thread is inside the GL driver: no destructors may run under it
}

}  // namespace foveal::daemon

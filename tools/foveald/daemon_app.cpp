#include "daemon_app.hpp"

#include <signal.h>
#include <sys/resource.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <set>

#include "foveal/core/data_paths.hpp"
#include "foveal/runtime/gaze_pipeline.hpp"
#include "foveal/tools/args.hpp"
#include "foveal/tools/cli.hpp"
#include "foveal/tools/log.hpp"

namespace foveal::daemon {

namespace {

constexpr const char* kDefaultLog = "data/gaze/vive_pro_eye_TESTNA01.csv";
constexpr std::uint64_t kWarmupFrames = 100;  // caches, driver pools and histograms are full by then

double peak_rss_mb() {
  rusage ru{};
  ::getrusage(RUSAGE_SELF, &ru);
  return static_cast<double>(ru.ru_maxrss) / 1024.0;
}

double current_rss_mb() {
  long pages = 0, resident = 0;
  if (std::FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
    std::fclose(f);
  }
  return static_cast<double>(resident) * static_cast<double>(::sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

int open_fds() {
  std::error_code ec;
  int n = 0;
  for (auto it = std::filesystem::directory_iterator("/proc/self/fd", ec); !ec && it != std::filesystem::directory_iterator();
       it.increment(ec))
    ++n;
  return n;
}

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

Result<Profile> DaemonApp::load_startup_profile() const {
  if (!o_.profile.empty()) return store_.load(o_.profile);
  const std::string active = store_.active();
  if (store_.exists(active)) return store_.load(active);
  Profile p;  // no profile yet: the built-in defaults (EFR seed pair)
  p.name = "default";
  return p;
}

Status DaemonApp::apply_profile(const Profile& p, const char* why) {
  // Display model: the command line wins, then the profile's.
  if (o_.display.empty() && !source_) {
    if (p.display_model != model_.name) {
      const std::string path = p.display_model.find('/') != std::string::npos
                                   ? p.display_model
                                   : data_path("data/display/" + p.display_model + ".json");
      auto m = DisplayModel::load(path);
      if (!m) return m.error();
      model_ = *m;
    }
  }
  const bool filter_changed = p.filter != profile_.filter;
  profile_ = p;
  settings_.store(RenderSettings::from(p, ++settings_generation_));
  if (loop_ && filter_changed) loop_->set_mapper(make_mapper());
  log::info(std::string("profile '") + p.name + "' " + why + ": dominant " + eye_name(p.dominant_eye) +
            ", sigma_d " + std::to_string(p.sigma_d) + ", sigma_nd " + std::to_string(p.sigma_nd));
  return {};
}

GazeLoop::Mapper DaemonApp::make_mapper() const {
  // The profile's filter section was validated when it was loaded.
  auto cfg = FilterConfig::from_json(profile_.filter, "profile " + profile_.name);
  auto pipe = std::make_shared<GazePipeline>(model_, cfg ? *cfg : FilterConfig{});
  return [pipe](const GazeSample& s) { return pipe->update(s); };
}

Status DaemonApp::setup() {
  auto profile = load_startup_profile();
  if (!profile) return profile.error();
  if (!o_.display.empty()) {
    auto m = DisplayModel::load(o_.display);
    if (!m) return m.error();
    model_ = *m;
  }
  if (Status s = apply_profile(*profile, "loaded"); !s) return s;

  replay_.path = o_.replay.empty() ? data_path(kDefaultLog) : o_.replay;
  replay_.speed = o_.speed;
  replay_.loop = o_.loop;
  replay_.start_s = o_.start_s;
  replay_.end_s = o_.end_s;
  if (o_.loop && !o_.end_s) return bad_input("--loop needs --end (a looping replay never ends)");
  source_ = std::make_unique<ReplaySource>(replay_);
  if (Status s = source_->open(); !s) return s;

  std::error_code ec;
  std::filesystem::create_directories(o_.out, ec);
  if (ec) return io_error(o_.out + ": cannot create output directory: " + ec.message());
  auto trace = cli::FoveaTrace::create(o_.out + "/trace.csv");
  if (!trace) return trace.error();
  trace_.emplace(std::move(trace.value()));
  // The compositor before the socket: a client that sees the socket sees a daemon ready to render.
  if (Status s = setup_renderer(); !s) return s;

  if (!o_.no_control) {
    auto c = ControlServer::listen(o_.control.empty() ? default_control_socket_path() : o_.control);
    if (!c) return c.error();
    control_.emplace(std::move(c.value()));
    log::info("control socket " + control_->path());
  }
  if (o_.shm) {
    auto s = FoveaShm::create(default_fovea_shm_name());
    if (s) shm_.emplace(std::move(s.value()));
    else log::warn(s.error().message + "; the fovea stream is off");
  }
  return {};
}

Status DaemonApp::setup_renderer() {
  if (!o_.render) {
    if (o_.drm) return bad_input("--drm needs the compositor (drop --no-render)");
    return {};
  }
  RenderOptions ro;
  ro.scene = o_.scene;
  ro.method = o_.method;
  ro.save_every = o_.save_every;
  ro.window = !o_.headless;
  ro.drm = o_.drm;
  ro.monitor = o_.monitor;
  const render::KmsWanted wanted = render::headset_output(model_);  // docs/headset.md
  if (o_.drm) {
    if (ro.window) return bad_input("--drm and --window exclude each other");
    ro.drm_options.device = o_.drm_device;
    ro.drm_options.wanted = wanted;
    ro.drm_options.wanted.connector = o_.connector;
    if (!o_.mode.empty())
      if (Status s = render::parse_mode(o_.mode, ro.drm_options.wanted); !s) return s;
  }
  if (ro.window && o_.monitor == "auto") {
    auto c = render::find_headset_connector(wanted);
    if (!c) return bad_input("--monitor auto: " + c.error().message);
    log::info("--monitor auto: the headset is on connector " + *c);
    ro.monitor = *c;
  }
  ro.distortion = o_.distortion;
  if (!o_.size.empty()) {
    auto size = cli::parse_size(o_.size, "--size");
    if (!size) return size.error();
    if (size->first % 2 != 0) return bad_input("--size: the width must be even (two eyes side by side)");
    ro.width = size->first;
    ro.height = size->second;
  }
  auto r = FrameRenderer::create(ro, model_, o_.out);
  if (!r) return r.error();
  renderer_ = std::move(*r);
  log::info("compositor: " + renderer_->renderer());
  return {};
}

void DaemonApp::serve_control(int timeout_ms) {
  if (control_) control_->poll(timeout_ms, [this](const nlohmann::json& r) { return handle(r); });
  else if (timeout_ms > 0) sleep_until_ns(monotonic_now_ns() + timeout_ms * kNsPerMs);
}

nlohmann::json DaemonApp::status_json() const {
  const GazeLoopStats st = loop_ ? loop_->stats() : GazeLoopStats{};
  RenderSettings rs;
  (void)settings_.load(rs);
  const double up_s = static_cast<double>(monotonic_now_ns() - started_) / 1e9;
  return {{"ok", true},
          {"state", st.ended ? "ended" : st.failed ? "failed" : terminated_ ? "stopped" : (loop_ && loop_->paused()) ? "paused" : "running"},
          {"uptime_s", up_s},
          {"source", {{"driver", "replay"}, {"path", replay_.path}, {"speed", replay_.speed}}},
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
          {"resident_mb", current_rss_mb()},
          {"render", renderer_ ? renderer_->stats_json() : nlohmann::json(nullptr)},
          {"control", {{"requests", control_ ? control_->requests_served() : 0}, {"bad_requests", control_ ? control_->bad_requests() : 0}}}};
}

nlohmann::json DaemonApp::handle(const nlohmann::json& req) {
  const std::string cmd = req.value("cmd", "");
  if (cmd == "status") return status_json();
  if (cmd == "fovea") {
    FoveaFrame f;
    if (!loop_ || !loop_->latest().load(f)) return error_reply("no fovea yet");
    nlohmann::json j = fovea_json(f);
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
    return status_json();
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
    }
    auto p = Profile::from_json(j, profile_.name, "set");
    if (!p) return error_reply(p.error().message);
    if (Status s = apply_profile(*p, "changed"); !s) return error_reply(s.error().message);
    return status_json();
  }
  if (cmd == "pause" || cmd == "resume") {
    if (loop_) loop_->set_paused(cmd == "pause");
    return status_json();
  }
  return error_reply("unknown request '" + cmd + "' (status, fovea, profiles, use, set, pause, resume)");
}

void DaemonApp::print_status_line() {
  if (o_.json || !log::enabled(log::Level::info) || !::isatty(STDERR_FILENO)) return;
  const TimeNs now = monotonic_now_ns();
  if (now - last_status_ < kNsPerSec / 4) return;
  last_status_ = now;
  const GazeLoopStats st = loop_->stats();
  FoveaFrame f;
  (void)loop_->latest().load(f);
  std::fprintf(stderr, "\rfoveald: %s %llu samples  latency p99 %.3f ms  L(%4.0f,%4.0f) %-8s R(%4.0f,%4.0f) %-8s ",
               loop_->paused() ? "paused " : "running", static_cast<unsigned long long>(st.samples),
               ms(st.latency_p99_ns), f.eyes[0].px.x, f.eyes[0].px.y, fovea_state_name(f.eyes[0].state),
               f.eyes[1].px.x, f.eyes[1].px.y, fovea_state_name(f.eyes[1].state));
}

nlohmann::json DaemonApp::summary_json() const {
  nlohmann::json j = status_json();
  j.erase("ok");
  j["display_model"] = model_.name;
  j["trace"] = o_.out + "/trace.csv";
  j["peak_rss_mb"] = peak_rss_mb();
  // Soak figures: resident memory and open descriptors after warm-up and at the end.
  if (warm_rss_mb_ >= 0)
    j["resources"] = {{"warm", {{"rss_mb", warm_rss_mb_}, {"fds", warm_fds_}}},
                      {"end", {{"rss_mb", current_rss_mb()}, {"fds", open_fds()}}},
                      {"rss_growth_mb", current_rss_mb() - warm_rss_mb_}};
  if (pacing_.count() > 0)
    j["pacing_error_ms"] = {{"p50", ms(pacing_.percentile(0.5))}, {"p99", ms(pacing_.percentile(0.99))},
                            {"max", ms(pacing_.max())}};
  return j;
}

int DaemonApp::run() {
  // Signals go to a signalfd read by this thread; every other thread has them blocked.
  sigset_t sigs;
  sigemptyset(&sigs);
  sigaddset(&sigs, SIGINT);
  sigaddset(&sigs, SIGTERM);
  sigaddset(&sigs, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &sigs, nullptr);
  const int sigfd = ::signalfd(-1, &sigs, SFD_NONBLOCK | SFD_CLOEXEC);

  started_ = monotonic_now_ns();
  if (Status s = setup(); !s) return cli::report(s.error(), "foveald");
  if (Status s = source_->start(); !s) return cli::report(s.error(), "foveald");

  const int eye_w = model_.eye_width, eye_h = model_.eye_height;
  loop_ = std::make_unique<GazeLoop>(
      *source_, make_mapper(),
      [this, eye_w, eye_h](const GazeSample& s, const FoveaFrame& f) {
        if (replay_.speed > 0) pacing_.add(monotonic_now_ns() - s.t_ns);
        trace_->write(f);
        if (shm_) shm_->publish(f, eye_w, eye_h);
      });
  loop_->start(o_.rt_priority);

  int rc = cli::kExitOk;
  TimeNs next_frame = monotonic_now_ns();
  while (!loop_->finished()) {
    if (renderer_) {
      // The render thread takes the latest fovea and settings without waiting for anyone.
      serve_control(0);
      FoveaFrame f;
      (void)loop_->latest().load(f);
      RenderSettings rs;
      (void)settings_.load(rs);
      if (Status s = renderer_->render(f, rs, model_); !s) {
        rc = cli::report(s.error(), "foveald");
        break;
      }
      if (renderer_->frames() == kWarmupFrames) warm_rss_mb_ = current_rss_mb(), warm_fds_ = open_fds();
      if ((o_.frames > 0 && renderer_->frames() >= o_.frames) || renderer_->window_closed()) break;
      if (o_.fps > 0) {
        next_frame += static_cast<TimeNs>(1e9 / o_.fps);
        sleep_until_ns(next_frame);
      }
    } else {
      serve_control(20);
    }
    signalfd_siginfo si{};
    while (sigfd >= 0 && ::read(sigfd, &si, sizeof si) == static_cast<ssize_t>(sizeof si)) {
      if (si.ssi_signo == SIGHUP) {
        auto p = store_.load(profile_.name);
        if (!p) log::error(p.error().message + "; keeping the last good profile");
        else if (Status s = apply_profile(*p, "reloaded"); !s) log::error(s.error().message);
      } else {
        terminated_ = true;
      }
    }
    if (terminated_) break;
    print_status_line();
  }
  loop_->stop();
  if (sigfd >= 0) ::close(sigfd);
  if (log::enabled(log::Level::info) && !o_.json && ::isatty(STDERR_FILENO)) std::fprintf(stderr, "\n");

  const GazeLoopStats st = loop_->stats();
  if (st.failed) rc = cli::report(bad_input(st.last_error), "foveald");
  if (Status s = trace_->commit(); !s) return cli::report(s.error(), "foveald");
  if (renderer_)
    if (Status s = renderer_->finish(); !s) return cli::report(s.error(), "foveald");
  const nlohmann::json summary = summary_json();
  if (Status s = write_file_atomically(o_.out + "/summary.json", summary.dump(2) + "\n"); !s)
    return cli::report(s.error(), "foveald");
  if (o_.json) cli::print_json(summary);
  else if (log::enabled(log::Level::info))
    std::printf("foveald: %s %llu samples from %s -> %s/trace.csv, %s/summary.json\n",
                terminated_ ? "stopped after" : "replayed", static_cast<unsigned long long>(st.samples),
                replay_.path.c_str(), o_.out.c_str(), o_.out.c_str());
  if (renderer_ && !o_.json && log::enabled(log::Level::info))
    std::printf("foveald: rendered %llu frames -> %s/frames.csv, %zu PNG in %s\n",
                static_cast<unsigned long long>(renderer_->frames()), o_.out.c_str(),
                renderer_->saved_frames(), o_.out.c_str());
  return rc;
}

}  // namespace foveal::daemon

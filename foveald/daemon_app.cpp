#include "daemon_app.hpp"
#include "daemon_output.hpp"
#include "output_target.hpp"

#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "foveal/core/data_paths.hpp"
#include "foveal/core/json_text.hpp"
#include "foveal/core/shown_text.hpp"
#include "foveal/runtime/args.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/runtime/gaze_pipeline.hpp"
#include "foveal/runtime/jod_levels.hpp"
#include "foveal/runtime/log.hpp"
#include "process_stats.hpp"

namespace foveal::daemon {

namespace {

constexpr const char* kDefaultLog = "data/gaze/vive_pro_eye_TESTNA01.csv";
constexpr std::uint64_t kWarmupFrames = 100;  // caches, driver pools and histograms are full by then

/// The settings as other programs see them in the shared block (docs/fovea-shm.md).
FoveaShmSettings shm_settings(const RenderSettings& r) {
  FoveaShmSettings s{};
  s.sigma_d = r.sigma_d;
  s.sigma_nd = r.sigma_nd;
  s.f_x = r.f_x;
  s.f_y = r.f_y;
  s.dominant_eye = r.dominant_eye;
  s.generation = r.generation;
  return s;
}

}  // namespace

Result<Profile> DaemonApp::load_startup_profile() const {
  Result<Profile> p = Profile{};
  if (!o_.profile.empty()) {
    p = store_.load(o_.profile);
  } else if (auto active = store_.active(); !active) {
    return active.error();
  } else if (store_.exists(*active)) {
    p = store_.load(*active);
  } else {
    p->name = "default";  // no profile yet: the built-in defaults (EFR seed pair)
  }
  if (!p || o_.quality.empty()) return p;
  if (auto q = parse_quality(o_.quality, "--quality"); !q) return q.error();
  p->quality = o_.quality == "off" ? "" : o_.quality;  // the command line wins, until a profile is loaded again
  return p;
}

Status DaemonApp::apply_profile(const Profile& p, const char* why) {
  // Display model: the command line wins, then the profile's; fixed once the source runs.
  if (o_.display.empty() && !loop_) {
    if (p.display_model != model_.name) {
      auto m = DisplayModel::load(display_model_path(p.display_model));
      if (!m) return m.error();
      model_ = *m;
    }
  }
  // Levels chosen by perception replace the profile's own (its pair gives the EFR ratio).
  JodLevels chosen;
  auto levels = apply_quality(p, o_.display.empty() ? display_model_path(p.display_model) : display_model_path(o_.display), &chosen);
  if (!levels) return levels.error();
  const bool filter_changed = p.filter != profile_.filter;
  profile_ = p;
  const RenderSettings rs = RenderSettings::from(*levels, ++settings_generation_);
  settings_.store(rs);
  if (shm_) shm_->publish_settings(shm_settings(rs));
  if (loop_ && filter_changed) loop_->set_mapper(make_mapper());
  log::info(std::string("profile '") + p.name + "' " + why + ": dominant " + eye_name(p.dominant_eye) +
            ", sigma_d " + shown_number(levels->sigma_d) + ", sigma_nd " + shown_number(levels->sigma_nd) +
            (p.quality.empty() ? "" : ", f " + shown_number(chosen.f) + " (quality " + p.quality + ": predicted JOD " +
                                          shown_number(chosen.jod_d) + " dominant, " +
                                          (std::isfinite(chosen.jod_nd) ? shown_number(chosen.jod_nd) : "past the table") +
                                          " non-dominant)"));
  return {};
}

GazeLoop::Mapper DaemonApp::make_mapper() const {
  // The profile's filter section was validated when it was loaded.
  auto cfg = FilterConfig::from_json(profile_.filter, "profile " + profile_.name);
  auto pipe = std::make_shared<GazePipeline>(model_, cfg ? *cfg : FilterConfig{});
  return [pipe](const GazeSample& s) { return pipe->update(s); };
}

Status DaemonApp::setup_source() {
  if (!o_.replay.empty() && !o_.source.empty()) return bad_input("--replay PATH is short for --source replay:PATH: give one");
  source_text_ = !o_.source.empty() ? o_.source : "replay:" + (o_.replay.empty() ? data_path(kDefaultLog) : o_.replay);
  auto spec = probe::parse_source_spec(source_text_);
  if (!spec) return spec.error();
  if (o_.loop && !o_.end_s) return bad_input("--loop needs --end (a looping replay never ends)");
  probe::SourceOptions so;
  so.replay.speed = o_.speed;
  so.replay.loop = o_.loop;
  so.replay.start_s = o_.start_s;
  so.replay.end_s = o_.end_s;
  so.log = [](const std::string& line) { log::warn(line); };
  auto made = probe::make_source(*spec, so);
  if (!made) return made.error();
  source_ = std::move(*made);
  // A file must be readable now; a device may come later (the gaze loop waits for it).
  if (!source_.live)
    if (Status s = source_.source->open(); !s) return s;
  return setup_head(so);
}

Status DaemonApp::setup_head(const probe::SourceOptions& so) {
  // The camera follows the head when the source knows its pose, or a headset's own
  // tracking (docs/daemon.md, "Head pose"; docs/headset.md).
  const bool has_pose = !source_.live && source_.source->info().head_pose;
  auto head = HeadSide::create(o_.head, has_pose, source_text_, so);
  if (!head) return head.error();
  head_ = std::move(*head);
  // A headset's own lens data wins over the profile's model; --display over both.
  if (const auto& d = head_->headset_display(); d && o_.display.empty()) {
    model_ = d->model;
    log::info("display model from the headset: " + d->source);
  }
  return {};
}

double DaemonApp::output_refresh_hz() const {
  // The display's (direct mode knows its mode's rate); otherwise --fps, the display
  // model's, or 90 Hz.
  if (renderer_ && renderer_->refresh_hz() > 0) return renderer_->refresh_hz();
  if (o_.fps > 0) return o_.fps;
  return model_.refresh_hz > 0 ? model_.refresh_hz : 90.0;
}

Status DaemonApp::setup(const Profile& profile) {
  if (o_.duration_s && !(*o_.duration_s > 0)) return bad_input("--duration must be > 0 seconds");
  if (!o_.display.empty()) {
    auto m = DisplayModel::load(display_model_path(o_.display));
    if (!m) return m.error();
    model_ = *m;
  }
  if (Status s = apply_profile(profile, "loaded"); !s) return s;
  if (Status s = setup_source(); !s) return s;

  std::error_code ec;
  std::filesystem::create_directories(o_.out, ec);
  if (ec) return io_error(o_.out + ": cannot create output directory: " + ec.message());
  // Every output's target before any work: one AtomicFile would refuse at the end must
  // not cost a session its summary (output_target.hpp).
  if (Status s = check_output_target(o_.out + "/summary.json"); !s) return s;
  if (o_.render) {
    if (Status s = check_output_target(o_.out + "/frames.csv"); !s) return s;
    if (Status s = FrameRenderer::check_png_targets(o_.out, o_.save_every, o_.frames); !s) return s;
  }
  if (o_.trace) {
    auto trace = cli::FoveaTrace::create(o_.out + "/trace.csv");
    if (!trace) return trace.error();
    trace_.emplace(std::move(trace.value()));
  } else {
    trace_.emplace(cli::FoveaTrace::off());
  }
  // The compositor before the socket: a client that sees the socket sees a daemon ready to render.
  if (Status s = setup_renderer(); !s) return s;

  if (!o_.no_control) {
    auto c = ControlServer::listen(o_.control.empty() ? default_control_socket_path() : o_.control);
    if (!c) return c.error();
    control_.emplace(std::move(c.value()));
    control_->set_logger([](const std::string& line) { log::warn("control: " + line); });
    log::info("control socket " + control_->path());
  }
  if (o_.shm) {
    auto s = FoveaShm::create(default_fovea_shm_name());
    if (s) {
      shm_.emplace(std::move(s.value()));
      RenderSettings rs;
      (void)settings_.load(rs);
      shm_->publish_settings(shm_settings(rs));  // those of the startup profile, before any fovea
      shm_->publish_view(model_);                // fixed from here on: the source is set up
    } else {
      log::warn(s.error().message + "; the fovea stream is off");
    }
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
  ro.pipeline = o_.pipeline;
  if (!o_.temporal.empty()) ro.temporal = o_.temporal == "on";
  ro.blend_at = o_.blend_at;
  ro.save_every = o_.save_every;
  ro.output.title = "foveald";
  ro.output.monitor = o_.monitor;
  if (!o_.headless) ro.output.kind = render::OutputOptions::Kind::window;
  const render::KmsWanted wanted = render::headset_output(model_);  // docs/headset.md
  if (o_.drm) {
    if (!o_.headless) return bad_input("--drm and --window exclude each other");
    ro.output.kind = render::OutputOptions::Kind::drm;
    ro.output.drm.device = o_.drm_device;
    ro.output.drm.wanted = wanted;
    ro.output.drm.wanted.connector = o_.connector;
    if (!o_.mode.empty())
      if (Status s = render::parse_mode(o_.mode, ro.output.drm.wanted); !s) return s;
  }
  if (!o_.headless && o_.monitor == "auto") {
    auto c = render::find_headset_connector(wanted);
    if (!c) return bad_input("--monitor auto: " + c.error().message);
    log::info("--monitor auto: the headset is on connector " + *c);
    ro.output.monitor = *c;
  }
  ro.distortion = o_.distortion;
  ro.late_latch = o_.latch != "early";
  ro.prediction.enabled = o_.predict != "off";
  const bool display = ro.output.kind != render::OutputOptions::Kind::headless;
  auto pacing = parse_pacing(o_.pacing.empty() ? (display ? "jit" : "asap") : o_.pacing);
  if (!pacing) return pacing.error();
  if (*pacing == Pacing::jit && !display) return bad_input("--pacing jit needs a display (--window or --drm): headless frames have no refresh to meet");
  ro.pacing = *pacing;
  if (!o_.size.empty()) {
    auto size = cli::parse_size(o_.size, "--size");
    if (!size) return size.error();
    if (size->first % 2 != 0) return bad_input("--size: the width must be even (two eyes side by side)");
    ro.width = size->first;
    ro.height = size->second;
  }
  // The refresh to pace to (direct mode's mode replaces it once open); none headless.
  if (display) ro.refresh_hz = output_refresh_hz();
  auto r = FrameRenderer::create(ro, model_, o_.out);
  if (!r) return r.error();
  renderer_ = std::move(*r);
  log::info("compositor: " + renderer_->renderer());
  return {};
}

bool DaemonApp::deadline_passed() const {
  return o_.duration_s && monotonic_now_ns() - started_ >= static_cast<TimeNs>(*o_.duration_s * 1e9);
}

bool DaemonApp::claim_shutdown(Owner who) {
  int expected = nobody;
  return shutdown_owner_.compare_exchange_strong(expected, who);
}

int DaemonApp::render_loop() {
  TimeNs next_frame = monotonic_now_ns();
  const double refresh_hz = output_refresh_hz();  // the pose prediction's horizon
  while (!loop_->finished() && !stopping() && !deadline_passed()) {
    if (!renderer_) {
      sleep_until_ns(monotonic_now_ns() + 10 * kNsPerMs);
      continue;
    }
    // Just in time: sleep until the pacer's start, in steps so that a stop is seen.
    const FramePlan plan = renderer_->plan_next_frame(monotonic_now_ns());
    while (!stopping() && monotonic_now_ns() < plan.start_ns)
      sleep_until_ns(std::min(plan.start_ns, monotonic_now_ns() + 10 * kNsPerMs));
    // The render thread takes the latest fovea and settings without waiting for anyone;
    // the fovea again at the latch.
    const auto latest = [this] {
      FoveaFrame f;
      if (!loop_->latest().load(f)) f = FoveaFrame{};
      return f;
    };
    RenderSettings rs;
    (void)settings_.load(rs);
    // Recorded: the head where it was when the newest gaze sample was taken; a headset:
    // where it will be when the frame is shown. Fixed at the start: the first pass needs
    // the camera.
    const PoseAt head = head_->for_frame(latest().t_ns, refresh_hz);
    if (Status s = renderer_->render(latest, rs, model_, head, plan); !s) return report(s.error());
    const std::uint64_t frames = renderer_->frames();
    if (frames == kWarmupFrames) warm_rss_mb_ = current_rss_mb(), warm_fds_ = open_fds();
    if ((o_.frames > 0 && frames >= o_.frames) || renderer_->window_closed()) break;
    if (o_.fps > 0 && renderer_->pacing() == Pacing::asap) {  // jit paces itself, to the refresh
      next_frame += static_cast<TimeNs>(1e9 / o_.fps);
      // Sleep in steps so that a stop request is seen promptly.
      while (!stopping() && monotonic_now_ns() < next_frame)
        sleep_until_ns(std::min(next_frame, monotonic_now_ns() + 10 * kNsPerMs));
    }
  }
  return cli::kExitOk;
}

int DaemonApp::run() {
  // The profile store's files first, while SIGTERM still works: they are opened without
  // blocking (a FIFO is refused), and nothing else may stand between a signal and us.
  auto profile = load_startup_profile();
  if (!profile) return report(profile.error());
  // Signals go to a signalfd read by the control thread; every thread has them blocked.
  sigset_t sigs;
  sigemptyset(&sigs);
  sigaddset(&sigs, SIGINT);
  sigaddset(&sigs, SIGTERM);
  sigaddset(&sigs, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &sigs, nullptr);
  const int sigfd = ::signalfd(-1, &sigs, SFD_NONBLOCK | SFD_CLOEXEC);

  started_ = monotonic_now_ns();
  if (Status s = setup(*profile); !s) return report(s.error());
  if (!source_.live)
    if (Status s = source_.source->start(); !s) return report(s.error());

  const int eye_w = model_.eye_width, eye_h = model_.eye_height;
  const bool paced = source_.spec.driver != "replay" || o_.speed > 0;
  loop_ = std::make_unique<GazeLoop>(
      *source_.source, make_mapper(),
      [this, eye_w, eye_h, paced](const GazeSample& s, const FoveaFrame& f) {
        if (paced) pacing_.add(monotonic_now_ns() - s.t_ns);
        head_->push_recorded(s);
        trace_->write(f, markers_.take_until(f.t_ns));
        if (shm_) shm_->publish(f, eye_w, eye_h);
      },
      /*wait_for_source=*/source_.live);
  // Until the first sample, and while a lost device is waited for, frames and `ctl fovea`
  // show the optical centre (docs/daemon.md, "Rendering").
  loop_->set_no_gaze(no_gaze_fovea(eye_w, eye_h));
  if (source_.live) log::info("source " + source_.spec.text() + ": waiting for the device");
  loop_->start(o_.rt_priority);
  head_->start();
  control_thread_ = std::thread([this, sigfd] { control_thread(sigfd); });

  const int rc = render_loop();
  if (!claim_shutdown(main_thread)) {
    // The control thread took over while a frame was in flight and ends the process.
    for (;;) ::pause();
  }
  control_stop_ = true;
  control_thread_.join();
  if (sigfd >= 0) ::close(sigfd);
  return shutdown(rc);
}

int DaemonApp::shutdown(int rc) {
  loop_->stop();
  head_->stop();
  if (log::enabled(log::Level::info) && !o_.json && ::isatty(STDERR_FILENO)) log::raw("\n");  // ends the status line
  const GazeLoopStats st = loop_->stats();
  if (st.failed) rc = report(bad_input(st.last_error));
  trace_->write_markers(markers_.take_all());  // those after the last sample
  if (Status s = trace_->commit(); !s) return report(s.error());
  // A frame that could not be saved ends the session, but with its summary and
  // frames.csv: the error is reported once, where it happened.
  if (renderer_)
    if (Status s = renderer_->finish(/*save_last=*/!stopping()); !s) rc = report(s.error());
  const nlohmann::json summary = summary_json();
  if (Status s = write_file_atomically(o_.out + "/summary.json", json_text(summary, 2) + "\n"); !s)
    return report(s.error());
  // stdout may be a pipe nobody reads as well: these lines wait for it a little only.
  if (o_.json) {
    print_json(summary);
  } else if (log::enabled(log::Level::info)) {
    std::string text = std::string("foveald: ") + (stopping() ? "stopped after " : "read ") + std::to_string(st.samples) +
                       " samples from " + source_text_ + " -> " + o_.out + "/trace.csv, " + o_.out + "/summary.json\n";
    if (renderer_)
      text += "foveald: rendered " + std::to_string(renderer_->frames()) + " frames -> " + o_.out + "/frames.csv, " +
              std::to_string(renderer_->saved_frames()) + " PNG in " + o_.out + "\n";
    (void)log::out(text, kOutputStallMs);
  }
  return rc;
}

}  // namespace foveal::daemon

// foveald: the runtime daemon. Reads gaze from any source the prober knows (a tracker,
// or by default a replay of the bundled real Vive Pro Eye recording): a gaze thread maps
// samples to a fovea per eye and publishes them (exchange, shared memory, trace), a
// control thread serves the socket and signals, the main thread renders.
#include <CLI/CLI.hpp>

#include <signal.h>

#include <algorithm>
#include <cstdio>

#include "daemon_app.hpp"
#include "daemon_output.hpp"
#include "service_options.hpp"
#include "foveal/drivers/probe.hpp"
#include "foveal/image/foveation_plan.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/runtime/log.hpp"
#include "foveal/version.h"

namespace {

struct Flags {
  int verbose = 0, quiet = 0;
  bool service = false, print_config = false;
  std::string config;
};

/// foveald's options, defined once: the command line is parsed by them, and again with
/// the options file's entries in front when there is one (service_options.hpp).
void define_options(CLI::App& app, foveal::daemon::Options& o, Flags& f) {
  app.set_version_flag("--version", "foveald " FOVEAL_VERSION);
  app.add_option("--source,-s", o.source, "Gaze source (default: replay of the bundled Vive Pro Eye recording):\n" +
                                             foveal::probe::source_spec_help());
  app.add_option("--replay", o.replay, "Short for --source replay:PATH");
  app.add_option("--duration", o.duration_s, "Stop after this many seconds, whatever the source");
  app.add_option("--head", o.head, "Camera: recorded (the log's head pose moves it), static (the scene's view), or a headset's own tracking, predicted to each frame's display time:\n" +
                                       foveal::probe::pose_spec_help() + "default: recorded when the log has a pose, else static");
  app.add_option("--display", o.display, "Display model: a name under data/display or a JSON file (default: the profile's, else htc_vive_pro_eye)");
  app.add_option("--profile", o.profile, "User profile (default: the active one, else built-in defaults)");
  app.add_option("--out,-o", o.out, "Output directory: trace.csv, frames.csv, frame_*.png, summary.json")->capture_default_str();
  app.add_option("--speed", o.speed, "Replay speed: 1 real time, 0 as fast as possible")->capture_default_str();
  app.add_option("--start", o.start_s, "Replay from this time (s from the log's first sample)");
  app.add_option("--end", o.end_s, "Replay until this time (s from the log's first sample)");
  app.add_flag("--loop", o.loop, "Loop the replay window (needs --end)");
  app.add_option("--control", o.control, "Control socket path (default: $XDG_RUNTIME_DIR/foveal/control.sock)");
  app.add_flag("--no-control", o.no_control, "Do not open the control socket");
  app.add_flag("!--no-shm", o.shm, "Do not publish the fovea in shared memory");
  app.add_option("--realtime", o.rt_priority, "Run the gaze thread with SCHED_FIFO at this priority (1-99; needs CAP_SYS_NICE)")
      ->check(CLI::Range(1, 99));
  app.add_flag("--headless", o.headless, "Render without a window through EGL (the default)");
  app.add_flag("!--window", o.headless, "Show the frames in a window (fullscreen with --monitor)");
  app.add_option("--monitor", o.monitor, "Window mode: fullscreen on the monitor whose name contains this; auto: the connector direct mode would take");
  auto* drm = app.add_flag("--drm", o.drm, "Direct mode: show the frames on a DRM/KMS connector, no display server (docs/headset.md)");
  app.add_option("--drm-device", o.drm_device, "Direct mode: the card node (default: the first /dev/dri/card* with a matching output)")
      ->needs(drm);
  app.add_option("--connector", o.connector, "Direct mode: connector name, e.g. DP-1 (default: the non-desktop or EDID-matching one)")
      ->needs(drm);
  app.add_option("--mode", o.mode, "Direct mode: WxH or WxH@HZ (default: the display model's size and refresh rate)")->needs(drm);
  app.add_flag("--render,!--no-render", o.render, "Run the compositor (the default; off for --service unless set) or only the gaze side");
  app.add_flag("--trace,!--no-trace", o.trace,
               "Write every sample's fovea to OUT/trace.csv at exit (the default; off for --service unless set: ~45 MB an hour "
               "held until exit)");
  app.add_flag("!--no-distortion", o.distortion, "Ignore the display model's lens distortion");
  app.add_option("--frames", o.frames, "Stop after this many frames (default: when the replay ends)");
  app.add_option("--fps", o.fps, "Headless frame rate (default: as fast as the renderer goes)")->check(CLI::Range(0.0, 1000.0));
  app.add_option("--scene", o.scene, "glTF file or pattern:NAME (default: the bundled Dungeon)");
  app.add_option("--pipeline", o.pipeline, "gbuffer or visibility (docs/rmfr.md, \"Pipelines\")")
      ->check(CLI::IsMember(foveal::render::pipeline_names()))->capture_default_str();
  app.add_option("--temporal", o.temporal,
                 "on or off: foveated temporal accumulation, RMFR in the visibility pipeline (docs/rmfr.md, \"Temporal "
                 "accumulation\"; default: the profile's temporal key, off)")
      ->check(CLI::IsMember({"on", "off"}));
  app.add_option("--blend-at", o.blend_at,
                 "output or samples: where alphaMode BLEND and transmissive surfaces are shaded: at output resolution after the "
                 "inverse pass, or at the samples the method keeps, before it (visibility pipeline; docs/rmfr.md, \"Transparency "
                 "at the kept samples\")")
      ->check(CLI::IsMember(foveal::render::blend_at_names()))->capture_default_str();
  app.add_option("--method", o.method, "One of " + foveal::render::method_names_joined(", "))
      ->check(CLI::IsMember(foveal::render::method_names()))->capture_default_str();
  app.add_option("--pacing", o.pacing, "When frames start: jit (just in time before each refresh) or asap (default: jit on a display, asap headless; docs/latency.md)")
      ->check(CLI::IsMember({"asap", "jit"}));
  app.add_option("--latch", o.latch, "When a frame reads the fovea: late (after the passes that do not need it) or early (at its start)")
      ->check(CLI::IsMember({"late", "early"}))
      ->capture_default_str();
  app.add_option("--quality", o.quality, "Levels chosen by perception: jod:T picks sigma_d, sigma_nd and f that hold predicted JOD >= T "
                                         "from the display model's table (docs/methods.md); off: the profile's levels. Default: the profile's quality");
  app.add_option("--predict", o.predict, "Predict the fovea to each frame's display time: on or off (docs/filtering.md, \"Prediction\")")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  app.add_option("--size", o.size, "Side-by-side output WxH (default: the display model's, 2880x1600)");
  app.add_option("--save-every", o.save_every, "Also save every Nth frame as PNG (the first and last always)")->check(CLI::Range(0, 1000000));
  app.add_flag("--json", o.json, "Print the summary as JSON");
  app.add_flag("-v,--verbose", f.verbose, "More log output (repeatable); also $FOVEAL_LOG=debug|info|warn|error");
  app.add_flag("-q,--quiet", f.quiet, "Less log output, no live status line");
  app.add_flag("--service", f.service,
               "Run as the user service: wait for the tracker and the headset (--source auto --head auto), serve the "
               "fovea without rendering, options from $XDG_CONFIG_HOME/foveal/foveald.conf (docs/daemon.md, \"Service\")");
  app.add_option("--config", f.config, "Options file (default with --service: $XDG_CONFIG_HOME/foveal/foveald.conf); "
                                       "the command line wins over it");
  app.add_flag("--print-config", f.print_config, "Print the options file's keys as this run would use them, and exit");
}

int parse_error(CLI::App& app, const CLI::ParseError& e) {
  const int rc = app.exit(e);
  return rc == 0 ? 0 : foveal::cli::kExitBadInput;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"foveald: the foveal runtime daemon (gaze -> fovea -> compositor)"};
  foveal::daemon::Options o;
  Flags f;
  define_options(app, o, f);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return parse_error(app, e);
  }
  if (f.service || !f.config.empty()) {
    // Parsed again with the file's entries (and the service's defaults) in front of the
    // command line's, so each value meets the same checks as on the command line.
    const std::string path = f.config.empty() ? foveal::daemon::default_config_path() : f.config;
    auto args = foveal::daemon::service_arguments(path, f.service, [&](const std::string& option) { return app.count(option) > 0; });
    if (!args) {
      std::fprintf(stderr, "foveald: %s\n", args.error().message.c_str());
      return foveal::cli::kExitBadInput;
    }
    for (int i = 1; i < argc; ++i) args->emplace_back(argv[i]);
    CLI::App again{app.get_description()};
    o = {};
    f = {};
    define_options(again, o, f);
    std::reverse(args->begin(), args->end());  // CLI11 takes a vector last argument first
    try {
      again.parse(*args);
    } catch (const CLI::ParseError& e) {
      if (e.get_exit_code() == 0) return parse_error(again, e);
      std::fprintf(stderr, "foveald: %s: %s\n", path.c_str(), e.what());
      return foveal::cli::kExitBadInput;
    }
  }
  if (f.print_config) {
    std::fputs(foveal::daemon::config_text(o).c_str(), stdout);
    return 0;
  }
  o.verbosity = f.verbose - f.quiet;
  foveal::log::init("foveald", o.verbosity);
  // stderr (or stdout) may be a pipe nobody reads, or whose reader died: lines go through
  // a queue to a thread of their own (dropped and counted when it is full), no write to
  // either may wait for the reader (log.hpp), and a dead reader is an EPIPE, never a
  // SIGPIPE that kills foveald with its outputs uncommitted.
  ::signal(SIGPIPE, SIG_IGN);
  foveal::log::start_writer_thread();
  const int rc = foveal::daemon::DaemonApp(o).run();
  foveal::log::flush(foveal::daemon::kOutputStallMs);  // the last lines, unless stderr is stuck
  return rc;
}

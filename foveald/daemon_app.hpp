#pragma once
// foveald's composition root: wires the gaze source (any spec the prober knows), the
// gaze loop (driver -> mapper -> exchange), the control plane, shared memory, signals
// and the compositor.
//
// Threads (docs/daemon.md):
//   main     setup, then the render loop (GLFW wants the main thread), then shutdown
//   gaze     GazeLoop: source -> filter -> latest fovea, trace, shared memory
//   control  the control socket and the signals; never waits for a frame
// Settings go from the control thread to the renderer through a SeqLock (latest value).
#include <atomic>
#include <memory>
#include <optional>
#include <thread>

#include <nlohmann/json.hpp>

#include "foveal/core/display_model.hpp"
#include "foveal/core/pose_track.hpp"
#include "foveal/drivers/probe.hpp"
#include "foveal/runtime/control_server.hpp"
#include "foveal/runtime/fovea_shm.hpp"
#include "foveal/runtime/fovea_trace.hpp"
#include "foveal/runtime/gaze_loop.hpp"
#include "foveal/runtime/profile.hpp"
#include "foveal/runtime/trace_markers.hpp"
#include "frame_renderer.hpp"
#include "head_side.hpp"
#include "options.hpp"
#include "render_settings.hpp"

namespace foveal::daemon {

class DaemonApp {
 public:
  explicit DaemonApp(Options o) : o_(std::move(o)) {}
  /// Runs until the source ends, --duration or --frames is reached, or SIGINT/SIGTERM;
  /// returns the exit code.
  int run();

 private:
  // Setup (main thread, before the other threads start).
  Status setup(const Profile& startup_profile);
  Status setup_source();
  Status setup_head(const probe::SourceOptions& so);
  double output_refresh_hz() const;  // the display's refresh: pacing and the pose prediction's horizon
  Status setup_renderer();
  Result<Profile> load_startup_profile() const;
  Status apply_profile(const Profile& p, const char* why);  // main, then control thread
  GazeLoop::Mapper make_mapper() const;

  // The main thread's loop and the orderly shutdown.
  int render_loop();
  bool deadline_passed() const;
  int shutdown(int rc);

  // The control thread (daemon_control.cpp).
  void control_thread(int signal_fd);
  void handle_signals(int signal_fd);
  nlohmann::json handle(const nlohmann::json& request);
  nlohmann::json status_json() const;
  nlohmann::json source_json() const;
  nlohmann::json summary_json() const;
  void print_status_line();
  /// The frame in flight is too slow to wait for: commit what is complete, write the
  /// summary and end the process (exit code 0).
  [[noreturn]] void emergency_exit();

  /// Who shuts down: the main thread after its loop, or the control thread when the main
  /// thread is still inside a frame kEmergencyAfterNs after a stop request.
  enum Owner : int { nobody = 0, main_thread = 1, control = 2 };
  bool claim_shutdown(Owner who);

  Options o_;
  ProfileStore store_ = ProfileStore::user();
  Profile profile_;                     // control thread after setup
  std::uint32_t settings_generation_ = 0;
  SeqLock<RenderSettings> settings_;    // written by the control thread, read by the renderer
  DisplayModel model_ = DisplayModel::vive_pro_eye();
  std::string source_text_;             // the spec, for status
  probe::OpenedSource source_;
  std::unique_ptr<GazeLoop> loop_;
  std::unique_ptr<HeadSide> head_;  // the camera's pose: recorded, static or a headset (head_side.hpp)
  std::optional<cli::FoveaTrace> trace_;
  cli::MarkerQueue markers_;  // `ctl mark`: control thread in, gaze thread out into the trace
  std::optional<ControlServer> control_;  // control thread after setup
  std::optional<FoveaShm> shm_;
  std::unique_ptr<FrameRenderer> renderer_;  // render() on the main thread only
  LatencyHistogram pacing_;  // gaze thread only until the loop has stopped
  std::thread control_thread_;
  std::atomic<bool> control_stop_{false};
  std::atomic<TimeNs> stop_requested_at_{0};  // when SIGINT/SIGTERM came; 0: not (yet)
  bool stopping() const { return stop_requested_at_.load() > 0; }
  std::atomic<int> shutdown_owner_{nobody};
  std::atomic<double> warm_rss_mb_{-1};  // resident memory and fds after the warm-up frames
  std::atomic<int> warm_fds_{0};
  TimeNs started_ = 0;
  TimeNs last_status_ = 0;
};

}  // namespace foveal::daemon

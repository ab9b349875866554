#pragma once
// foveald's composition root: wires the gaze source, the gaze loop (driver -> mapper ->
// exchange), the control socket, shared memory, signals and the outputs.
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "foveal/core/display_model.hpp"
#include "foveal/drivers/replay_source.hpp"
#include "foveal/runtime/control_server.hpp"
#include "foveal/runtime/fovea_shm.hpp"
#include "foveal/runtime/gaze_loop.hpp"
#include "foveal/runtime/profile.hpp"
#include "options.hpp"
#include "foveal/tools/fovea_trace.hpp"
#include "frame_renderer.hpp"
#include "render_settings.hpp"

namespace foveal::daemon {

class DaemonApp {
 public:
  explicit DaemonApp(Options o) : o_(std::move(o)) {}
  /// Runs until the source ends or SIGINT/SIGTERM; returns the exit code.
  int run();

 private:
  Status setup();
  Status apply_profile(const Profile& p, const char* why);
  Result<Profile> load_startup_profile() const;
  GazeLoop::Mapper make_mapper() const;
  nlohmann::json handle(const nlohmann::json& request);
  nlohmann::json status_json() const;
  nlohmann::json summary_json() const;
  void print_status_line();
  Status setup_renderer();
  void serve_control(int timeout_ms);

  Options o_;
  ProfileStore store_ = ProfileStore::user();
  Profile profile_;
  std::uint32_t settings_generation_ = 0;
  SeqLock<RenderSettings> settings_;
  DisplayModel model_ = DisplayModel::vive_pro_eye();
  ReplayOptions replay_;
  std::unique_ptr<ReplaySource> source_;
  std::unique_ptr<GazeLoop> loop_;
  std::optional<cli::FoveaTrace> trace_;
  std::optional<ControlServer> control_;
  std::optional<FoveaShm> shm_;
  std::unique_ptr<FrameRenderer> renderer_;  // main thread only
  LatencyHistogram pacing_;  // gaze thread only until the loop has stopped
  bool terminated_ = false;  // stopped by SIGINT/SIGTERM
  double warm_rss_mb_ = -1;  // resident memory and fds after the warm-up frames
  int warm_fds_ = 0;
  TimeNs started_ = 0;
  TimeNs last_status_ = 0;
};

}  // namespace foveal::daemon

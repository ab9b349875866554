#pragma once
// foveald's render side: the compositor driven by the latest fovea and the active
// render settings, once per frame on the render (main) thread; it never waits for the
// gaze or control threads. Keeps per-frame stats (frames.csv), saves chosen frames as
// PNG and publishes a snapshot of its stats that any thread may read (`status`,
// summary.json) without waiting for a frame.
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/core/atomic_file.hpp"
#include "foveal/core/pose_source.hpp"
#include "foveal/render/compositor.hpp"
#include "foveal/render/output.hpp"
#include "foveal/render/scene.hpp"
#include "foveal/runtime/fovea.hpp"
#include "foveal/runtime/fovea_prediction.hpp"
#include "frame_latency.hpp"
#include "frame_pacer.hpp"
#include "render_settings.hpp"

namespace foveal::daemon {

struct RenderOptions {
  std::string scene;              ///< glTF path or pattern:NAME
  std::string method = "rmfr";
  std::string pipeline = render::kDefaultPipelineName;  ///< gbuffer or visibility (docs/rmfr.md)
  std::optional<bool> temporal;   ///< temporal accumulation (--temporal); unset: the profile's
  std::string blend_at = "output";  ///< output or samples (--blend-at; samples needs the visibility pipeline)
  int width = 0, height = 0;      ///< 0: the display model's side-by-side size
  int save_every = 0;             ///< also save every Nth frame (0: first and last only)
  render::OutputOptions output;   ///< headless, window or direct mode
  bool distortion = true;         ///< the display model's lens distortion, if any
  /// Read the fovea at the compositor's late latch (after the first full-resolution
  /// pass); false: at the frame's start, as before the latch existed (docs/latency.md).
  bool late_latch = true;
  Pacing pacing = Pacing::asap;   ///< when frames start (frame_pacer.hpp)
  /// The latched fovea predicted to the frame's display target (fovea_prediction.hpp).
  FoveaPrediction prediction;
  double refresh_hz = 0;          ///< the display's, for pacing; 0: none (headless)
};

class FrameRenderer {
 public:
  /// Opens the output (EGL headless, a GLFW window or a DRM/KMS connector), loads the
  /// scene, builds the compositor, creates DIR/frames.csv. Render thread.
  static Result<std::unique_ptr<FrameRenderer>> create(const RenderOptions& o, const DisplayModel& model,
                                                       const std::string& out_dir);
  ~FrameRenderer();

  /// When the next frame should start and the refresh it is for (RenderOptions::pacing).
  /// Render thread.
  FramePlan plan_next_frame(TimeNs now) const;
  /// Renders one frame with `settings`, started now for `plan`. `latest` gives the newest
  /// fovea (viewport pixels of `model`; the gaze pipeline has already decided what a lost
  /// eye shows) and is called at the latch (RenderOptions::late_latch), and once at the
  /// start. `head`: the head pose for the frame (invalid: the scene's own view); the
  /// camera moves by its pose relative to the first one, and frames.csv records it.
  /// frames.csv gets the frame's row once its shown time is known (docs/latency.md).
  /// Render thread.
  Status render(const std::function<FoveaFrame()>& latest, const RenderSettings& settings, const DisplayModel& model,
                const PoseAt& head, const FramePlan& plan);
  /// Saves the last frame (if `save_last` and not yet saved: a 2880x1600 PNG takes about
  /// a second on llvmpipe, too long after SIGTERM), commits frames.csv. Render thread.
  Status finish(bool save_last);
  /// From any thread, while render() may be running: commits frames.csv with the
  /// frames completed so far; the frame in flight (if any) is dropped, and nothing is
  /// written after this. For a shutdown that cannot wait for a slow frame.
  Status abandon();
  bool window_closed() const { return output_->closed(); }
  /// The name frame N is saved under (in the output directory).
  static std::string png_name(std::uint64_t frame);
  /// bad_input naming the first PNG target (and with `frames` > 0 the last and every
  /// `save_every`-th) that is not absent or a regular file: refused before any work,
  /// as trace.csv, frames.csv and summary.json are.
  static Status check_png_targets(const std::string& out_dir, int save_every, std::uint64_t frames);

  std::uint64_t frames() const;   ///< any thread
  std::size_t saved_frames() const;  ///< any thread
  const std::string& renderer() const { return renderer_name_; }
  Pacing pacing() const { return o_.pacing; }
  /// The display's refresh the frames are paced to (direct mode: its mode's; a window:
  /// RenderOptions::refresh_hz); 0 headless.
  double refresh_hz() const { return refresh_hz_; }
  /// Any thread: the stats as of the last completed frame.
  nlohmann::json stats_json() const;

 private:
  FrameRenderer() = default;
  Status save_frame();
  Status estimate_f(const render::FrameParams& p);
  /// frames.csv rows of the frames whose shown time the output now knows.
  Status write_shown_rows();

  /// A presented frame waiting for its shown time: its row without the latency cells.
  struct PendingRow {
    std::string cells;
    FrameLatency latency;
    TimeNs ready_ns = 0;  ///< Output::last_ready_ns: the frame's cost for pacing
    double blend_ms = 0;  ///< the last column (PassTimes::blend), after the latency's
  };

  /// What other threads may read, updated after each frame under snapshot_mutex_.
  struct Snapshot {
    std::uint64_t frames = 0;
    render::FrameParams last_params;
    std::array<std::array<int, 2>, 2> buffers{};
    std::vector<render::PassTimes> recent;  ///< ring of the last 128 frames
    std::uint32_t generation = 0;
    std::uint64_t settings_changes = 0;
    std::optional<std::pair<double, double>> auto_f;
    nlohmann::json output;
    double targets_mb = 0, temporal_mb = 0;  ///< all render targets; temporal accumulation's histories
    int blend_layers = 0;                     ///< the last frame's, composited at the kept samples
    std::vector<std::string> saved;
    nlohmann::json latency, pacing;
  };

  RenderOptions o_;
  std::string out_dir_;
  std::string renderer_name_, scene_name_;
  std::array<int, 2> size_{};  ///< the output's width and height
  double refresh_hz_ = 0;
  std::unique_ptr<render::Output> output_;
  std::optional<render::Scene> scene_;
  std::optional<render::Compositor> comp_;
  render::Method method_ = render::Method::rmfr;
  render::Pipeline pipeline_ = render::Pipeline::gbuffer;
  render::BlendAt blend_at_ = render::BlendAt::output;
  std::mutex csv_mutex_;  ///< frames.csv: written by render(), committed by finish() or abandon()
  std::optional<AtomicFile> csv_;
  bool csv_closed_ = false;
  std::uint64_t frames_ = 0, saved_frame_ = ~0ull;  ///< render thread
  std::uint32_t last_generation_ = 0;
  std::deque<PendingRow> pending_;  ///< render thread; at most a frame or two
  std::optional<TimeNs> last_shown_;
  LatencyStats latency_;
  std::optional<FramePacer> pacer_;
  // Automatic f: estimated from a full frame when the settings ask for it and change.
  std::optional<std::uint32_t> auto_f_generation_;
  double auto_fx_ = 0.3, auto_fy_ = 0.3;
  mutable std::mutex snapshot_mutex_;
  Snapshot snap_;
};

}  // namespace foveal::daemon

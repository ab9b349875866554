#pragma once
// foveald's render side: the compositor driven by the latest fovea and the active
// render settings, once per frame on the main thread (it never waits for the gaze
// thread). Keeps per-frame stats (frames.csv), saves chosen frames as PNG and exposes
// a summary for `status` and summary.json.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/core/atomic_file.hpp"
#include "foveal/render/compositor.hpp"
#include "foveal/render/drm_output.hpp"
#include "foveal/render/egl_context.hpp"
#include "foveal/render/scene.hpp"
#include "foveal/render/window.hpp"
#include "foveal/runtime/fovea.hpp"
#include "render_settings.hpp"

namespace foveal::daemon {

struct RenderOptions {
  std::string scene;              ///< glTF path or pattern:NAME
  std::string method = "rmfr";
  int width = 0, height = 0;      ///< 0: the display model's side-by-side size
  int save_every = 0;             ///< also save every Nth frame (0: first and last only)
  bool window = false;
  bool drm = false;               ///< direct mode (render/drm_output.hpp)
  render::DrmOutputOptions drm_options;  ///< device, connector, mode
  bool distortion = true;         ///< the display model's lens distortion, if any
  std::string monitor;            ///< fullscreen on this monitor (window mode)
};

class FrameRenderer {
 public:
  /// Opens the output (EGL headless, a GLFW window or a DRM/KMS connector), loads the
  /// scene, builds the compositor, creates DIR/frames.csv.
  static Result<std::unique_ptr<FrameRenderer>> create(const RenderOptions& o, const DisplayModel& model,
                                                       const std::string& out_dir);
  ~FrameRenderer();

  /// Renders one frame for `fovea` (viewport pixels of `model`) with `settings`.
  /// A lost or never-seen eye keeps its last fovea (the centre at first).
  Status render(const FoveaFrame& fovea, const RenderSettings& settings, const DisplayModel& model);
  /// Saves the last frame (if not yet saved), commits frames.csv.
  Status finish();
  bool window_closed() const;

  std::uint64_t frames() const { return frames_; }
  std::size_t saved_frames() const { return saved_.size(); }
  std::string renderer() const { return comp_->renderer(); }
  nlohmann::json stats_json() const;

 private:
  FrameRenderer() = default;
  Status save_frame();
  nlohmann::json output_json() const;
  Status estimate_f(const render::FrameParams& p);

  RenderOptions o_;
  std::string out_dir_;
  std::optional<gl::EglContext> egl_;
  std::optional<render::Window> window_;
  std::optional<render::DrmOutput> drm_;
  std::optional<render::Scene> scene_;
  std::optional<render::Compositor> comp_;
  render::Method method_ = render::Method::rmfr;
  std::optional<AtomicFile> csv_;
  std::array<glm::dvec2, 2> last_fovea_{glm::dvec2(0.5), glm::dvec2(0.5)};
  render::FrameParams last_params_;
  std::vector<render::PassTimes> recent_;  ///< ring of the last 128 frames
  std::uint64_t frames_ = 0, saved_frame_ = ~0ull;
  std::vector<std::string> saved_;
  std::uint32_t last_generation_ = 0;
  // Automatic f: estimated from a full frame when the settings ask for it and change.
  std::optional<std::uint32_t> auto_f_generation_;
  double auto_fx_ = 0.3, auto_fy_ = 0.3;
  std::uint64_t settings_changes_ = 0;
};

}  // namespace foveal::daemon

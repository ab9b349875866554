#pragma once
// How `foveal metrics` reads its images (docs/metrics.md, "Stereo frames and ppd"): one
// image or two eyes side by side, and the one pixels-per-degree that every metric of the
// call (PSNR/SSIM/FPSNR or JOD) uses.
#include <optional>
#include <string>

#include "foveal/core/display_model.hpp"
#include "foveal/core/error.hpp"

namespace foveal::evaluation {

struct FrameChoice {
  std::string display;                ///< --display: a name under data/display or a path; empty: the default model
  bool stereo = false, mono = false;  ///< --stereo, --mono (the CLI makes them exclusive)
  std::optional<double> ppd;          ///< --ppd, when given
  /// foveal render's default --size ("WxH"), which a frame is detected as stereo at; the
  /// CLI passes it, so that this room does not include the CLI's options.
  std::string render_size;
};

struct MetricsFrame {
  bool stereo = false;
  std::string stereo_from;  ///< "detected", "--stereo" or "--mono"
  std::string detected_as;  ///< a detected stereo frame: whose size it has
  int width = 0, height = 0, eye_width = 0, eye_height = 0;
  /// The display (given or the default); with --ppd a symmetric one of the eye image's
  /// size with that ppd at its centre, which JOD then scores on.
  DisplayModel model;
  std::string display_name;  ///< the display's name (with --ppd too: it chose the stereo rule)
  double ppd = 0;
  std::string ppd_from;  ///< "--ppd" or "display"

  /// "stereo (detected: ...), 13.15 ppd (...)": the rules, for the output line.
  std::string summary() const;
};

/// The display model --display names, resolved as `bench --display` does
/// (display_model_path): a name under data/display or a path; empty: the default.
Result<DisplayModel> load_metrics_display(const std::string& spec);

/// The frame of `width` × `height` (the reference's, or its first frame's) under `choice`:
/// stereo when --stereo, one image when --mono, and otherwise stereo exactly when the
/// size is the display's side-by-side output (2·eye_width × eye_height) or foveal render's
/// default --size. The ppd: --ppd, else the display's eye at the eye image's size
/// (perception::eye_geometry, what JOD scores with).
Result<MetricsFrame> metrics_frame(const FrameChoice& choice, int width, int height);

}  // namespace foveal::evaluation

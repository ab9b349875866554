#pragma once
// A native FovVideoVDP (Mantiuk et al., "FovVideoVDP: A visible difference predictor for
// wide field-of-view video", ACM TOG 40(4), 2021): the quality of a test image or video
// against its reference in JOD (just-objectionable differences; 10 = no visible difference),
// for one eye's view on a display model, foveated at a fixation point per frame or not.
// docs/metrics.md, "JOD", lists the model's parts and every departure from the reference.
#include <memory>
#include <optional>
#include <vector>

#include "foveal/core/display_model.hpp"
#include "foveal/core/error.hpp"
#include "foveal/image/image.hpp"
#include "foveal/perception/parameters.hpp"

namespace foveal::perception {

/// Where one eye's image pixels point: focal length and principal point in pixels of an
/// image of width × height (pixel i covers [i, i+1)).
struct EyeGeometry {
  int width = 0, height = 0;
  double focal_px = 0, cx = 0, cy = 0;
  /// Pixels per degree at the principal point.
  double ppd() const;
};

/// The eye `e` of `model` seen through an image of w × h: the model's focal length and
/// principal point scaled by w / eye_width and h / eye_height (an image at the viewport's
/// size gives the model's own).
EyeGeometry eye_geometry(const DisplayModel& model, Eye e, int w, int h);

/// The luminance the model takes (its CSF table's span, cd/m²): black and peak within.
inline constexpr double kMinLuminanceCdM2 = 0.001, kMaxLuminanceCdM2 = 10000;

/// The panel's light: sRGB-encoded values shown between black and peak (cd/m²).
/// Defaults: FovVideoVDP's HTC Vive Pro (133.3 and 0.1 cd/m²). validate(): finite,
/// kMinLuminanceCdM2 <= black < peak <= kMaxLuminanceCdM2.
struct Photometry {
  double peak_cd_m2 = 133.3;
  double black_cd_m2 = 0.1;
  Status validate() const;
};

/// A fixation point in image pixels (continuous: the centre of pixel i is i + 0.5).
struct Fixation {
  double x = 0, y = 0;
};

struct JodScore {
  double jod = 10;   ///< 10 minus the predicted visible difference
  double q = 0;      ///< the pooled difference before the JOD regression
  int frames = 0;
  int bands = 0;     ///< pyramid bands scored
  double ppd = 0;
};

class JodMetric {
 public:
  /// `threads` (≥ 1) share each frame's pyramid and pooling.
  JodMetric(EyeGeometry geometry, Photometry photometry, Parameters parameters = {}, int threads = 1);
  ~JodMetric();
  JodMetric(JodMetric&&) noexcept;
  JodMetric& operator=(JodMetric&&) noexcept;

  const EyeGeometry& geometry() const;
  /// A still: `test` against `reference` (both geometry().width × height); no fixation:
  /// foveal sensitivity everywhere.
  Result<JodScore> still(const image::Image& reference, const image::Image& test,
                         const std::optional<Fixation>& fixation) const;

  /// A video fed frame by frame at `fps` (frames before the first repeat it).
  class Video {
   public:
    Status push(const image::Image& reference, const image::Image& test, const std::optional<Fixation>& fixation);
    /// The score over the frames pushed so far (bad_input when none).
    Result<JodScore> score() const;
    ~Video();
    Video(Video&&) noexcept;

   private:
    friend class JodMetric;
    struct State;
    explicit Video(std::unique_ptr<State> s);
    std::unique_ptr<State> s_;
  };
  /// fps must be finite and > 0.
  Result<Video> video(double fps) const;

  struct Impl;

 private:
  std::shared_ptr<const Impl> impl_;
};

/// The JOD of a pooled difference Q under `p`: 10 + a·Q^(10^log_jod_exp).
double jod_from_q(double q, const Parameters& p);

}  // namespace foveal::perception

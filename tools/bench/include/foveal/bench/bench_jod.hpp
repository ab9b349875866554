#pragma once
// JOD (FovVideoVDP, foveal::perception) of the bench's side-by-side frames: each eye
// scored alone as its eye of the display model, at its own fixation, like the bench's
// FPSNR (docs/bench.md, "JOD"). The panel's light is `foveal metrics --jod`'s default
// unless the bench's --peak and --black give another.
#include <array>
#include <chrono>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/core/display_model.hpp"
#include "foveal/core/error.hpp"
#include "foveal/image/image.hpp"
#include "foveal/perception/jod.hpp"

namespace foveal::bench {

/// A normalised fovea of one eye's image ([0,1]², origin top-left); none: not foveated.
using EyeFovea = std::optional<std::array<double, 2>>;

struct StereoJod {
  double left = 10, right = 10;
  double combined = 10;  ///< the JOD of both eyes' mean pooled difference (as metrics --jod)
};

/// JOD of still stereo frames at one output size, and the time it has cost.
class StereoJodScorer {
 public:
  /// `width` × `height`: the side-by-side frame (even width, an eye at least 8×8);
  /// `light`: the panel's peak and black luminance (refused unless 0 < black < peak).
  static Result<StereoJodScorer> create(const DisplayModel& model, int width, int height, int threads = 2,
                                        const perception::Photometry& light = {});

  Result<StereoJod> still(const image::Image& reference, const image::Image& test, const EyeFovea& left, const EyeFovea& right);

  /// Pixels per degree of an eye as the metric sees it (at its principal point).
  double ppd(Eye e) const;
  const perception::Photometry& photometry() const { return photometry_; }
  /// Frames scored so far and the wall time they took.
  int scored() const { return scored_; }
  double total_ms() const { return total_ms_; }

  /// A video of stereo frames at `fps`, each eye along its own fixations.
  class Video {
   public:
    Status push(const image::Image& reference, const image::Image& test, const EyeFovea& left, const EyeFovea& right);
    Result<StereoJod> score() const;

   private:
    friend class StereoJodScorer;
    Video(StereoJodScorer& owner, std::vector<perception::JodMetric::Video> eyes) : owner_(&owner), eyes_(std::move(eyes)) {}
    StereoJodScorer* owner_;
    std::vector<perception::JodMetric::Video> eyes_;
  };
  Result<Video> video(double fps);

 private:
  StereoJodScorer(std::vector<perception::JodMetric> eyes, const perception::Photometry& light, int eye_w, int eye_h)
      : eyes_(std::move(eyes)), photometry_(light), eye_w_(eye_w), eye_h_(eye_h) {}
  Status check(const image::Image& reference, const image::Image& test) const;
  std::optional<perception::Fixation> fixation(const EyeFovea& f) const;
  StereoJod combine(const perception::JodScore& l, const perception::JodScore& r) const;

  std::vector<perception::JodMetric> eyes_;  ///< left, right
  perception::Photometry photometry_;
  perception::Parameters parameters_;
  int eye_w_ = 0, eye_h_ = 0;
  int scored_ = 0;
  double total_ms_ = 0;
};

/// bench.json's (gaze.json's) "jod": how the JOD columns were scored, and their cost.
nlohmann::json jod_settings(const StereoJodScorer& j);
/// After the progress bar: what JOD added per frame, of the run's time since `start`.
void print_jod_cost(const StereoJodScorer& j, const char* label, std::chrono::steady_clock::time_point start);

}  // namespace foveal::bench

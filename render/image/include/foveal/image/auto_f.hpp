#pragma once
// Automatic f_x, f_y for RMFR ("model no more than a scene needs"; the RMFR paper leaves
// it open). RMFR's output is fully determined by the full-resolution frame: every lit
// texel is the full frame's pixel at the texel's source pixel (same G-buffer sample, same
// lighting), resolved bilinearly. So the CPU can predict RMFR's image for any f from one
// full frame, and a coordinate search over log f maximises the predicted FPSNR. Cost: a
// few dozen CPU resamplings against the grid search's renders (docs/methods.md).
#include <array>

#include "foveal/image/image.hpp"
#include "foveal/image/metrics.hpp"

namespace foveal::image {

struct AutoF {
  double fx = 0.3, fy = 0.3;
  double predicted_fpsnr_db = 0;  ///< of the side-by-side frame, as compute_stereo_metrics
  int evaluations = 0;
  double ms = 0;  ///< wall time of the estimate
};

/// `full` is a side-by-side frame rendered with the full method; `sigma` per eye (left,
/// right); the foveae and ppd from `mo`. f is searched in [0.05, 1.0].
/// Errors: an empty or odd-width frame, σ < 1.
Result<AutoF> estimate_rmfr_f(const Image& full, std::array<double, 2> sigma, const MetricsOptions& mo);
inline Result<AutoF> estimate_rmfr_f(const Image& full, double sigma, const MetricsOptions& mo) {
  return estimate_rmfr_f(full, {sigma, sigma}, mo);
}

/// RMFR's image of one eye predicted from its full-resolution image: buffer texel
/// (i, j) takes the pixel at floor(inverse((i + 0.5)/w) · W), then bilinear back.
Image simulate_rmfr(const Image& full_eye, double sigma, double fx, double fy, double fovea_x, double fovea_y);

}  // namespace foveal::image

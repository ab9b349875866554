#pragma once
// RMFR in image space: an image is mapped forward into the reduced buffer (w×h) with an
// area prefilter, then back to full size with bilinear filtering. For the seeds'
// image-based experiments on photographs (`foveal foveate`).
#include "foveal/image/image.hpp"

namespace foveal::image {

struct FoveateParams {
  double sigma = 2.0;            ///< W/w = H/h; 1 = no reduction
  double fx = 0.3, fy = 0.3;     ///< mapping parameter per axis, fraction of W and H
  double fovea_x = 0.5, fovea_y = 0.5;  ///< normalised, origin top-left
};

struct FoveateResult {
  Image reduced;  ///< the w×h buffer
  Image output;   ///< back at the input's size
};

/// Errors: sigma < 1 or not finite, f <= 0 or not finite (bad_input).
Result<FoveateResult> foveate(const Image& in, const FoveateParams& p);

}  // namespace foveal::image

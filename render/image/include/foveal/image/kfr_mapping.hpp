#pragma once
// KFR's kernel log-polar mapping (Meng et al. 2018) on the radius axis, in the direction
// of the authors' public Unity shaders (xmeng525/KernelFoveatedRendering_Unity): pass 1
// fills buffer column u ∈ [0, 1] from the screen radius r = exp(L · u^(1/α)), pass 2 reads
// a screen pixel at radius r from u = (ln r / L)^α. L is the log of the largest distance
// (pixels) from the fovea to a viewport corner; α = 4 is the authors' default. With α > 1
// this spreads the buffer's columns outwards compared with plain log-polar (α = 1), which
// would spend most of them on the first few pixels around the fovea (docs/methods.md).
// The same formulas are KFR's GLSL kernel (render/image/src/methods/kfr.cpp); tests hold
// the two together.
#include <algorithm>
#include <cmath>

#include "foveal/image/image.hpp"

namespace foveal::image {

/// L for a viewport of W×H pixels and a fovea at (cx, cy) pixels: ln of the distance to
/// the farthest corner, that distance taken as at least 2 pixels (so L > 0).
inline double kfr_log_max(int W, int H, double cx, double cy) {
  const double dx = std::max(cx, W - cx), dy = std::max(cy, H - cy);
  return std::log(std::max(std::hypot(dx, dy), 2.0));
}

/// Buffer -> screen: the distance from the fovea (pixels) that buffer column u samples.
inline double kfr_radius(double u, double log_max, double alpha) { return std::exp(log_max * std::pow(u, 1.0 / alpha)); }

/// Screen -> buffer: the buffer column read by a pixel at distance r from the fovea
/// (r below one pixel counts as one: the log-polar map has no centre).
inline double kfr_column(double r, double log_max, double alpha) {
  return std::pow(std::log(std::max(r, 1.0)) / log_max, alpha);
}

/// KFR's image of one eye predicted from its full-resolution image, as the compositor
/// makes it: buffer texel (i, j) of the round(W/σ) × round(H/σ) buffer takes the pixel at
/// radius kfr_radius((i + 0.5)/w) and angle 2π(j + 0.5)/h around the fovea, and each
/// pixel reads the buffer bilinearly (in linear light, as from the GPU's sRGB buffer;
/// clamped along u, wrapping along the angle). fovea_y runs downwards like the image's rows.
Image simulate_kfr(const Image& full_eye, double sigma, double alpha, double fovea_x, double fovea_y);

/// Distinct screen pixels sampled by an eye's buffer (σ, α, fovea as above) per buffer
/// texel: how much of the shading the mapping spends on new samples rather than on
/// repeats of one pixel (near the fovea) or of the viewport's border (beyond its corners).
double kfr_distinct_fraction(int W, int H, double sigma, double alpha, double fovea_x, double fovea_y);

}  // namespace foveal::image

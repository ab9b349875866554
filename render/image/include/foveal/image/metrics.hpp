#pragma once
// Full-reference image quality metrics: PSNR, SSIM and foveated PSNR (FPSNR), on single
// images (one fovea) and side-by-side stereo frames (one fovea per half). Formulas,
// parameters and sources: docs/metrics.md.
#include <cstddef>

#include "foveal/image/image.hpp"

namespace foveal::image {

/// HTC Vive Pro Eye at the centre of the view (docs/metrics.md, DESIGN.md section 3).
constexpr double kDefaultPixelsPerDegree = 13.15;

/// Wang-Bovik foveation model constants (docs/metrics.md).
constexpr double kFoveaAlpha = 0.106;  ///< spatial frequency decay constant
constexpr double kFoveaE2 = 2.3;       ///< half-resolution eccentricity, degrees
constexpr double kFoveaCT0 = 1.0 / 64.0;  ///< minimum contrast threshold

/// What SSIM is computed on: BT.601 luma of the 8-bit sRGB values (the default), or
/// each of R, G, B separately and averaged.
enum class SsimChannels { luma, rgb };

/// A fovea in normalised image coordinates: [0,1] × [0,1], origin top-left, y down
/// (docs/conventions.md).
struct NormPoint {
  double x = 0.5, y = 0.5;
};

struct MetricsOptions {
  double ppd = kDefaultPixelsPerDegree;  ///< pixels per degree at the image (eye) centre
  NormPoint fovea;                       ///< single image, or the left eye of a stereo frame
  NormPoint fovea_right;                 ///< the right eye of a stereo frame
  SsimChannels ssim_channels = SsimChannels::luma;
};

struct Metrics {
  double psnr_db = 0;   ///< +infinity when identical
  double ssim = 0;      ///< 1 when identical
  double fpsnr_db = 0;  ///< +infinity when identical
  // The pooled quantities, so that regions can be combined.
  double mse = 0;       ///< mean of (a - b)² over R, G, B
  double fmse = 0;      ///< Σ w²·err² / Σ w², err² = mean over R, G, B of (a - b)²
  double weight_sum = 0;  ///< Σ w² (cycles/degree squared)
  std::size_t pixels = 0;
};

struct StereoMetrics {
  Metrics left, right;
  Metrics combined;  ///< PSNR and FPSNR from the pooled (weighted) MSE; SSIM the mean of both halves
};

/// Metrics of `test` against the reference `ref` with one fovea (`opt.fovea`).
/// Errors (bad_input): empty images, different sizes, smaller than the 11×11 SSIM
/// window, a fovea outside [0,1] or not finite, ppd not finite or <= 0.
Result<Metrics> compute_metrics(const Image& ref, const Image& test, const MetricsOptions& opt);

/// The same on a side-by-side stereo frame: the left half with `opt.fovea`, the right
/// half with `opt.fovea_right`, each half on its own (its own centre; SSIM windows do
/// not cross the seam). Also an error: an odd width.
Result<StereoMetrics> compute_stereo_metrics(const Image& ref, const Image& test, const MetricsOptions& opt);

/// Mean SSIM inside `r` (the window stays inside `r`): 11×11 Gaussian window σ 1.5,
/// K1 0.01, K2 0.03, L 255, over the positions where the whole window fits.
/// Errors: different sizes, `r` not inside the image or smaller than 11×11.
Result<double> ssim(const Image& a, const Image& b, Rect r, SsimChannels ch = SsimChannels::luma);
Result<double> ssim(const Image& a, const Image& b, SsimChannels ch = SsimChannels::luma);

/// Angle in degrees between the rays through `p` and `g` (pixels, measured from the
/// projection centre) on a planar image with focal length `f_px`.
double eccentricity_deg(double px, double py, double gx, double gy, double f_px);

/// Wang-Bovik cutoff frequency (cycles/degree) at eccentricity `ecc_deg`, capped at the
/// display's Nyquist frequency ppd / 2.
double foveation_cutoff_cpd(double ecc_deg, double ppd);

/// Focal length in pixels of a planar image with `ppd` pixels per degree at its centre.
double focal_length_px(double ppd);

}  // namespace foveal::image

#pragma once
// The Vive configuration's optics as a foveal display model (docs/display-model.md,
// "From a Vive's configuration"): the frustum from the intrinsics as Monado computes
// it, and the per-colour DISTORT_DPOLY3 distortion converted to the model the folded
// distortion pass uses (LensDistortion) by a least-squares fit, whose residual is
// reported.
#include <array>
#include <string>

#include "foveal/core/display_model.hpp"
#include "foveal/drivers/vive/vive_config.hpp"

namespace foveal::vive {

/// Where channel `c` (0 R, 1 G, 2 B) of panel point (u, v) (normalised, origin top-left)
/// samples the rendered image (normalised), by the configuration's own model (Monado's
/// u_compute_distortion_vive).
glm::dvec2 vive_source(const Config& cfg, int eye, int c, double u, double v);

/// The rendered image's frustum for `eye`: the intrinsics grown by grow_for_undistort.
EyeFrustum vive_frustum(const Config& cfg, int eye);

struct DistortionFit {
  std::array<double, 2> rms_px{}, max_px{};  ///< per eye, in rendered-image pixels
  std::size_t points = 0;                    ///< panel points fitted per eye and channel
};

/// The display model: name from the model number, the configuration's eye size, IPD
/// (lens_separation), frustum, and the fitted distortion; refresh 90 Hz and EDID vendor
/// "HVR" (both assumed: the configuration carries neither). `fit` receives the
/// residuals. Errors: a fit that does not give a valid model.
Result<DisplayModel> vive_display_model(const Config& cfg, DistortionFit* fit = nullptr);

/// A one-line description for the model file's "source" key.
std::string vive_model_source(const Config& cfg, const DistortionFit& fit);

}  // namespace foveal::vive

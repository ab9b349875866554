#pragma once
// What each foveation method shades for one eye, decided on the CPU once per frame:
// buffer sizes, mapping parameters and (for the layered methods) the layers. The
// compositor turns a plan into passes; the bench uses plans to compare methods at equal
// shaded-sample counts. Formulas and sources: docs/methods.md.
//
// Every method takes the same level σ: it shades about W·H/σ² samples (KFR and RMFR:
// a w×h buffer with w = round(W/σ); the layered methods scale their eccentricity
// thresholds until they shade that many). σ = 1 renders at full rate.
//
// Every point and rectangle here (EyeFoveation's fovea, EyePlan::fovea, Layer rectangles,
// eccentricity_deg, optical_centre) is in viewport coordinates with the origin at the
// top-left, y down (docs/conventions.md, "Display and pixels"). The one flip to GL's
// bottom-left origin is where the shader uniforms are bound (render/pipeline/src/method_binding.cpp).
#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "foveal/core/display_model.hpp"
#include "foveal/core/error.hpp"

namespace foveal::render {

// Each method is described in one file (foveal/image/method_description.hpp); its value
// is its row in the list (render/image/src/methods/method_list.cpp). The values named
// here are the rows code refers to by name (full the reference, rmfr for EFR and the
// bench, ...); the methods after them (inset, inset-fixed) are reached by name
// (parse_method). uniform and fixed are the choices without eye tracking
// (docs/methods.md): uniform shades a W/σ × H/σ grid and upsamples (RMFR's passes with
// the identity map); fixed is RMFR with the fovea pinned at the eye's optical centre.
enum class Method { full, rmfr, kfr, hyperbolic, linear, uniform, fixed };
const char* method_name(Method m);
/// One of method_names(); bad_input otherwise.
Result<Method> parse_method(const std::string& s);
/// Every method, full first.
const std::vector<Method>& all_methods();
/// Their names in the same order: the one list for command-line checks, help and defaults.
const std::vector<std::string>& method_names();
/// The names joined, e.g. "full,rmfr,kfr,hyperbolic,linear,uniform,fixed" for ",".
std::string method_names_joined(const std::string& separator);
/// Whether `m` is one of all_methods() (an enum value from elsewhere may not be).
bool is_method(Method m);

/// One eye's foveation for one frame.
struct EyeFoveation {
  double sigma = 1.0;                   ///< level, >= 1 (see above)
  double fx = 0.3, fy = 0.3;            ///< RMFR's f per axis, fractions of W and H, > 0
  double fovea_x = 0.5, fovea_y = 0.5;  ///< normalised, origin top-left of the eye's viewport;
                                        ///< NaN/Inf -> centre, outside [0,1] -> clamped
  double kfr_alpha = 4.0;               ///< KFR kernel exponent (Meng et al. recommend 4)
  double layer_scale = 0.0;             ///< layered methods: eccentricity scale; 0 = match σ's cost
  /// inset: the inner view's half-extent, degrees (its tangent at the optical centre, both
  /// axes); 0 = 35% of the frustum's tangent half-extent per axis (Quad-Views-Foveated's)
  double inset_deg = 0.0;
  double inset_band_deg = 3.0;          ///< inset: band over which the inner view blends in, degrees
};

/// One layer of the layered methods: a screen rectangle shaded at 1/pixel_size² rate.
struct Layer {
  double ecc_max_deg = 0;  ///< the layer serves pixels below this eccentricity (inf: the rest)
  double pixel_size = 1;   ///< screen pixels per buffer texel along each axis
  int x = 0, y = 0, w = 0, h = 0;           ///< screen rectangle, pixels, (x, y) its top-left corner
  int atlas_y = 0, buffer_w = 0, buffer_h = 0;  ///< where its texels sit in the eye's buffer
};

struct EyePlan {
  Method method = Method::full;
  int screen_w = 0, screen_h = 0;
  int buffer_w = 0, buffer_h = 0;  ///< the eye's reduced buffer (an atlas for layered methods)
  double sigma = 1;                ///< the level planned (EyeFoveation::sigma; 1 for full)
  glm::dvec2 fovea{0.5};           ///< normalised, origin top-left (sanitised; see FoveaSource)
  glm::dvec2 f{0.3};               ///< RMFR: effective f per axis (1e30 at σ = 1: no warp)
  double kfr_log_max = 1, kfr_alpha = 4;  ///< KFR: L = ln(largest fovea-corner distance, px)
  double layer_scale = 1;          ///< layered: the eccentricity scale used
  std::vector<Layer> layers;       ///< layered methods (hyperbolic, linear, inset), innermost first
  glm::dvec4 kernel_params{0.0};   ///< a kernel's own numbers (u_kernel_params; the inset's band)
  EyeFrustum frustum;              ///< for eccentricities

  /// Samples the lighting pass shades for this eye.
  std::size_t shaded_samples() const;
  /// Pixels per degree along x at the projection centre (for the FPSNR weights).
  double pixels_per_degree() const;
};

/// Plans one eye of W×H. Errors: σ < 1, f <= 0, alpha <= 0, negative layer scale.
Result<EyePlan> plan_eye(Method m, const EyeFoveation& f, int width, int height, const EyeFrustum& frustum);

/// Angle in degrees between the view rays through two points given in normalised
/// viewport coordinates (origin top-left), through the eye's frustum.
double eccentricity_deg(const EyeFrustum& frustum, glm::dvec2 p, glm::dvec2 q);

/// Where the eye's optical axis (direction (0,0,-1)) meets its viewport, normalised,
/// origin top-left: the fovea of the `fixed` method.
glm::dvec2 optical_centre(const EyeFrustum& frustum);

/// Whether the method's fovea follows the gaze (false for full, uniform and fixed).
bool follows_gaze(Method m);

}  // namespace foveal::render

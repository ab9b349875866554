#pragma once
// The HMD's per-eye geometry as data (docs/conventions.md, docs/display-model.md).
#include <array>
#include <string>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "foveal/core/error.hpp"
#include "foveal/core/gaze_sample.hpp"

namespace foveal {

/// Asymmetric frustum as tangents of the half-angles; left and bottom are negative.
struct EyeFrustum {
  float tan_left = -1.0f, tan_right = 1.0f, tan_bottom = -1.0f, tan_top = 1.0f;
};

/// Radial lens distortion with per-channel scale (chromatic aberration), docs/display-model.md.
/// For a panel pixel at normalised position p (origin top-left), with x = (p - center)
/// in tangent units of the eye's frustum and r² = |x|², channel c shows the rendered
/// (undistorted) image at center + x·scale[c]·(1 + k1 r² + k2 r⁴ + k3 r⁶).
struct LensDistortion {
  bool enabled = false;
  glm::vec2 center{0.5f, 0.5f};  ///< lens centre, normalised viewport coordinates
  float k1 = 0, k2 = 0, k3 = 0;
  glm::vec3 channel_scale{1.0f};  ///< R, G, B

  /// Where channel `c` of panel point `p` samples the rendered image (normalised).
  glm::vec2 source(glm::vec2 p, int c, const EyeFrustum& f) const;
  /// The inverse: the panel point whose channel `c` shows rendered point `src` (Newton
  /// on the radius); NaN when the polynomial does not reach it.
  glm::vec2 panel(glm::vec2 src, int c, const EyeFrustum& f) const;
};

/// Per-eye viewport size and projection. Pixel coordinates are those of the eye's
/// viewport: origin at the top-left corner, x right, y down, pixel i covers [i, i+1).
struct DisplayModel {
  std::string name;
  int eye_width = 1440;
  int eye_height = 1600;
  float ipd_mm = 63.0f;
  std::array<EyeFrustum, 2> frustum{};
  std::array<LensDistortion, 2> distortion{};  ///< disabled unless the model file has one
  /// The panel's refresh rate (Hz) for the output mode; 0: any (the connector's preferred).
  double refresh_hz = 0.0;
  /// EDID manufacturer ID (three letters, e.g. "HVR" for HTC's headsets) that marks the
  /// headset's connector or monitor; empty: match by mode size alone.
  std::string edid_vendor;

  const EyeFrustum& eye(Eye e) const { return frustum[static_cast<std::size_t>(e)]; }
  int output_width() const { return 2 * eye_width; }  ///< side by side, left eye left
  int output_height() const { return eye_height; }

  /// Gaze direction (eye frame, -z forward) -> viewport pixel. Directions at or behind
  /// the eye's plane give NaN. The result may lie outside the viewport.
  glm::vec2 direction_to_pixel(Eye e, glm::vec3 dir) const;
  /// Viewport pixel -> unit direction in the eye frame.
  glm::vec3 pixel_to_direction(Eye e, glm::vec2 px) const;
  /// Focal length in pixels along x and y (per eye).
  glm::vec2 focal_px(Eye e) const;
  /// Pixel where the optical axis (direction (0,0,-1)) lands.
  glm::vec2 principal_point(Eye e) const;

  /// HTC Vive Pro Eye, the default: FovVideoVDP's htc_vive_pro geometry (1440x1600,
  /// 110 deg diagonal, 753.6 px focal length, symmetric frustum).
  static DisplayModel vive_pro_eye();
  /// Loads a display-model JSON file (format in docs/display-model.md).
  static Result<DisplayModel> load(const std::string& path);
  /// The model in the file format load() reads (docs/display-model.md); `source` is
  /// written as the free-text "source" key when not empty.
  std::string to_json_text(const std::string& source = "") const;
  /// Checks sizes, ordering and finiteness of the tangents; message names `where`.
  Status validate(const std::string& where) const;
};

/// The file of a display model given as a name under data/display ("htc_vive_pro_eye")
/// or as a path (anything with a '/' or ending in .json).
std::string display_model_path(const std::string& spec);

}  // namespace foveal

#pragma once
// The Vive's configuration JSON (read from the headset, vive_reports.hpp) as data: the
// IMU calibration and the display's intrinsics and per-colour lens distortion, as
// Valve's Lighthouse HMD configuration documents the keys and Monado reads them.
#include <array>
#include <string>

#include <glm/vec3.hpp>

#include "foveal/core/error.hpp"
#include "foveal/core/imu_sample.hpp"
#include "foveal/drivers/vive/vive_reports.hpp"

namespace foveal::vive {

/// One colour channel's distortion (DISTORT_DPOLY3): its lens centre and coefficients.
struct ChannelDistortion {
  double center_x = 0, center_y = 0;  ///< normalised: panel centre 0, half the width 1
  std::array<double, 4> coeffs{};     ///< k1 k2 k3 (k4: the "scaled" variant's offset)
};

struct EyeOptics {
  /// intrinsics [[fx, 0, cx], [0, fy, cy], [0, 0, -1]], normalised by half the eye's
  /// width/height.
  double fx = 1, fy = 1, cx = 0, cy = 0;
  double grow_for_undistort = 0.5, undistort_r2_cutoff = 1;
  std::array<ChannelDistortion, 3> rgb{};  ///< distortion_red, distortion, distortion_blue
};

/// Which IMU axes flip into the runtime's (Monado's per-model mapping; unchecked here).
enum class Variant { vive, vive_pro };

struct Config {
  std::string model_number, serial;
  Variant variant = Variant::vive;
  int eye_width = 1080, eye_height = 1200;  ///< Monado's defaults when absent
  double ipd_m = 0.063;                     ///< lens_separation (or ipd.default_mm)
  double aspect_x_over_y = 0.9;             ///< device.physical_aspect_x_over_y
  std::array<EyeOptics, 2> eyes{};
  glm::vec3 acc_bias{0.0f}, acc_scale{1.0f}, gyro_bias{0.0f}, gyro_scale{1.0f};
};

/// Parses the JSON. Errors (bad_input) name `where` and the key path, e.g.
/// "vive config: tracking_to_eye_transform[1].intrinsics: expected a 3x3 array of numbers".
/// Required: a model (model_number or model_name), device.eye_target_width/height_in_pixels,
/// tracking_to_eye_transform with two eyes each with intrinsics and distortion; the
/// red/blue distortion default to green's, the IMU calibration to none.
Result<Config> parse_config(const std::string& json, const std::string& where = "vive config");

/// One raw IMU sample in SI units on the runtime's head axes: range/32768 · scale · raw
/// − bias (the config's calibration), then the variant's axis flip. t_ns is left to
/// the caller.
ImuSample imu_to_sample(const ImuRawSample& s, const Config& c, const ImuRange& range);

}  // namespace foveal::vive

#pragma once
// What `foveal metrics` does once its options are parsed (docs/metrics.md): PSNR, SSIM and
// FPSNR of a test image against a reference on one image or a side-by-side stereo frame,
// or with --jod FovVideoVDP's JOD of images and frame sequences, printed as text or JSON.
#include <string>

#include "foveal/core/error.hpp"
#include "foveal/image/metrics.hpp"

namespace foveal::evaluation {

/// The command's options as given (the CLI's defaults).
struct MetricsRequest {
  std::string ref, test, fovea, fovea_right, ssim_channels = "luma";
  double ppd = image::kDefaultPixelsPerDegree;
  bool ppd_given = false;
  bool stereo = false, mono = false, json = false;
  // --jod (docs/metrics.md, "JOD")
  bool jod = false;
  std::string display, fovea_list, jod_release = "1.2";
  double fps = 0, peak = 133.3, black = 0.1;
  bool fps_given = false;
  std::string render_size;  ///< foveal render's default --size, detected as a stereo frame (FrameChoice)
};

/// Checks the ranges, sizes the work against the memory bound, computes and prints the
/// metrics. Errors name the option or file; nothing is printed on an error.
Status run_metrics(const MetricsRequest& a);

}  // namespace foveal::evaluation

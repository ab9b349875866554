#pragma once
// The data-quality measures over one channel's samples (one eye, or binocular gaze), as
// docs/quality.md defines them: RMS-S2S, STD, BCEA, data loss, effective frequency, and
// the offset from a known target.
#include <cstdint>
#include <limits>
#include <optional>
#include <span>

#include "foveal/quality/fick_angles.hpp"

namespace foveal {

/// One recorded sample of a channel: its Fick angles, or not valid (no direction).
struct AngleSample {
  bool valid = false;
  FickAngles gaze;
};

/// The share of a bivariate normal distribution the BCEA ellipse holds.
constexpr double kBceaProbability = 0.68;

struct ChannelQuality {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::uint64_t samples = 0;         ///< recorded in the window
  std::uint64_t valid = 0;           ///< of them, with a valid direction
  double expected_samples = 0;       ///< the window's duration x the nominal rate
  double data_loss_pct = kNaN;       ///< 100 (1 - valid / expected): missing or invalid
  double invalid_pct = kNaN;         ///< 100 (1 - valid / recorded)
  double effective_frequency_hz = kNaN;  ///< valid / duration
  std::uint64_t s2s_pairs = 0;       ///< consecutive recorded samples both valid
  double rms_s2s_deg = kNaN, rms_s2s_x_deg = kNaN, rms_s2s_y_deg = kNaN;
  double std_deg = kNaN, std_x_deg = kNaN, std_y_deg = kNaN;  ///< population STD
  double bcea_deg2 = kNaN;           ///< at kBceaProbability
};

/// `samples` in recorded order; `duration_s` and `rate_hz` > 0 for the data-loss and
/// frequency figures. Measures that need more valid samples than there are stay NaN.
ChannelQuality measure_channel(std::span<const AngleSample> samples, double duration_s, double rate_hz);

/// The mean offset of the valid samples from a target, on the tangent screen through
/// the target (docs/quality.md): the centroid's distance and its two components.
struct TargetOffset {
  double offset_deg = 0;
  double x_deg = 0;  ///< positive: gaze to the right of the target
  double y_deg = 0;  ///< positive: gaze above the target
  std::uint64_t samples = 0;
};
/// nullopt when no sample is valid.
std::optional<TargetOffset> mean_offset(std::span<const AngleSample> samples, const FickAngles& target);

}  // namespace foveal

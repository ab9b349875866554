#pragma once
// Data quality of a gaze recording, per eye and binocular, over the whole recording or a
// window, with accuracy against known targets (docs/quality.md).
#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "foveal/core/error.hpp"
#include "foveal/core/gaze_marker.hpp"
#include "foveal/core/gaze_sample.hpp"
#include "foveal/quality/channel_quality.hpp"

namespace foveal {

/// The participant looked at `at` from start_s to end_s (seconds from the first sample).
struct QualityTarget {
  double start_s = 0, end_s = 0;
  FickAngles at;
  std::string where;  ///< "file:line", for messages
};

struct QualityOptions {
  std::optional<double> start_s, end_s;  ///< seconds from the first sample
  std::vector<QualityTarget> targets;
};

enum class QualityChannel : int { left = 0, right = 1, binocular = 2 };
constexpr int kQualityChannels = 3;
const char* quality_channel_name(QualityChannel c);

struct TargetQuality {
  QualityTarget target;
  double start_s = 0, end_s = 0;  ///< the target's window, clipped to the measured one
  std::array<ChannelQuality, kQualityChannels> channels;
  std::array<std::optional<TargetOffset>, kQualityChannels> offsets;
};

/// Mean over the targets with valid samples of their offsets (ETDQualitizer's summary).
struct Accuracy {
  double offset_deg = ChannelQuality::kNaN, x_deg = ChannelQuality::kNaN, y_deg = ChannelQuality::kNaN;
  std::size_t targets = 0;
};

struct GazeQuality {
  double rate_hz = 0;              ///< nominal, from the log header
  double median_interval_ms = 0;   ///< over the whole recording
  double start_s = 0, end_s = 0;   ///< the measured window, from the first sample
  double duration_s() const { return end_s - start_s; }
  /// "combined" (the tracker's combined gaze) or "mean of eyes".
  std::string binocular_source;
  std::array<ChannelQuality, kQualityChannels> channels;
  std::vector<TargetQuality> targets;
  std::array<Accuracy, kQualityChannels> accuracy;
};

/// The window from the first marker with text `from` to the first marker after it with
/// text `to`, in seconds from the first sample (for QualityOptions::start_s/end_s).
struct MarkerWindow {
  double start_s = 0, end_s = 0;
};
Result<MarkerWindow> window_between_markers(std::span<const GazeSample> samples, std::span<const GazeMarker> markers,
                                            const std::string& from, const std::string& to);

/// `samples` in time order (a gaze log's). Errors: an empty window, a target outside it.
Result<GazeQuality> compute_gaze_quality(std::span<const GazeSample> samples, double rate_hz,
                                         const QualityOptions& options);

}  // namespace foveal

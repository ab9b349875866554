#pragma once
// What `foveal log validate` reports about a gaze log.
#include <cstdint>
#include <string>
#include <vector>

#include "foveal/core/error.hpp"
#include "foveal/core/gaze_log.hpp"

namespace foveal {

/// A run of consecutive samples in which neither eye has a valid direction.
struct InvalidRun {
  std::uint64_t first_index = 0;  ///< 0-based sample index
  std::uint64_t samples = 0;
  double start_s = 0;             ///< from the first sample
  double duration_ms = 0;         ///< first invalid sample to the next valid one (or the last)
  std::string kind;               ///< "dropout" (< 50 ms), "blink" (50-500 ms), "loss" (> 500 ms)
  bool at_end = false;            ///< the log ends inside the run
};

struct GazeLogStats {
  GazeLogHeader header;
  std::uint64_t samples = 0;
  double duration_s = 0;
  double estimated_rate_hz = 0;   ///< intervals / time, ignoring gaps > 3x the median interval
  double median_interval_ms = 0;
  double invalid_pct[2] = {0, 0}; ///< per eye: samples without a valid direction
  double longest_gap_ms = 0;      ///< largest interval between consecutive samples
  double longest_gap_at_s = 0;
  std::vector<InvalidRun> invalid_runs;
  std::uint64_t blinks = 0;
  /// v2 logs: samples with a head pose, and how far the head got from its first pose
  /// (the largest rotation angle, degrees; the largest distance, metres).
  std::uint64_t head_pose_samples = 0;
  double head_max_turn_deg = 0;
  double head_max_travel_m = 0;
};

/// Classifies a run by duration (thresholds documented in docs/gaze-log.md).
const char* classify_invalid_run(double duration_ms);

/// Streams the log once; memory grows only with the number of invalid runs.
Result<GazeLogStats> compute_gaze_log_stats(const std::string& path);

}  // namespace foveal

#pragma once
// How far the fovea is from the gaze when the frame is seen, for a latency L: each
// sample at t is shown at t + L and compared with the recorded gaze at t + L
// (docs/results/latency/prediction.md). Used by `foveal predict-eval`.
#include <array>
#include <string>
#include <vector>

#include "foveal/core/display_model.hpp"
#include "foveal/core/gaze_sample.hpp"
#include "foveal/runtime/filter_config.hpp"
#include "foveal/runtime/fovea_prediction.hpp"

namespace foveal::evaluation {

/// What is shown at t + L.
enum class Shown : int {
  none,            ///< the raw sample at t (no filter, no prediction)
  filter,          ///< the gaze pipeline's output at t (as configured)
  filter_predict,  ///< the same pipeline with predict_ms = L (the older fixed-horizon option)
  predict,         ///< predict_fovea of the output at t to t + L
};
constexpr std::array<Shown, 4> kShown = {Shown::none, Shown::filter, Shown::filter_predict, Shown::predict};
const char* shown_name(Shown s);

/// What the eye does at t + L: the pipeline's own labels, read afterwards (a confirmed
/// saccade counts from its back-dated onset to its landing), so they do not lag.
enum class Phase : int { all, fixation, pursuit, saccade, onset };
constexpr std::array<Phase, 5> kPhases = {Phase::all, Phase::fixation, Phase::pursuit, Phase::saccade, Phase::onset};
const char* phase_name(Phase p);

/// The gaze at t + L: the recorded sample interpolated (its own noise in every column),
/// or a centred 5-sample mean of it (zero lag, less noise; blurs saccades).
enum class Truth : int { recorded, smoothed };
constexpr std::array<Truth, 2> kTruths = {Truth::recorded, Truth::smoothed};
const char* truth_name(Truth t);

struct ErrorStats {
  std::size_t n = 0;
  double p50 = 0, p95 = 0, p99 = 0, mean = 0;  ///< degrees
};

struct LatencyResult {
  double latency_ms = 0;
  /// [truth][phase][shown]
  std::array<std::array<std::array<ErrorStats, kShown.size()>, kPhases.size()>, kTruths.size()> stats{};
};

/// Errors pooled over both eyes, for each latency. The samples counted are those whose
/// eye is valid at t and whose truth at t + L exists (both neighbours valid, no gap):
/// the same set in every column.
std::vector<LatencyResult> evaluate_prediction(const std::vector<GazeSample>& samples, const DisplayModel& model,
                                               const FilterConfig& cfg, const std::vector<double>& latencies_ms,
                                               const FoveaPrediction& prediction);

/// Several logs' results pooled: recomputed from the errors, not averaged percentiles.
struct PredictionEvaluator {
  PredictionEvaluator(DisplayModel model, FilterConfig cfg, std::vector<double> latencies_ms, FoveaPrediction p);
  void add(const std::vector<GazeSample>& samples);
  std::vector<LatencyResult> result() const;

 private:
  DisplayModel model_;
  FilterConfig cfg_;
  std::vector<double> latencies_ms_;
  FoveaPrediction prediction_;
  /// [latency][truth][phase][shown] -> errors in degrees
  std::vector<std::array<std::array<std::array<std::vector<double>, kShown.size()>, kPhases.size()>, kTruths.size()>>
      errors_;
};

}  // namespace foveal::evaluation

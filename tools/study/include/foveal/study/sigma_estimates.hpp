#pragma once
// Estimates of sigma_UF and sigma_NF from the random test's scores (docs/study.md,
// "sigma_UF and sigma_NF"): where the mean score, as a piecewise-linear function of the
// level, first falls below a threshold.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "foveal/study/study_trials.hpp"

namespace foveal {

/// How an estimate was found: between two tested levels (interpolated), at or past the
/// largest tested level (at_least: no tested level fell below the threshold), or below
/// the smallest (below_range: the first tested level already fell below it).
enum class EstimateBound { interpolated, at_least, below_range };
const char* estimate_bound_name(EstimateBound b);

struct LevelScore {
  double sigma_d = 1, sigma_nd = 1;
  std::size_t trials = 0;
  double mean = 0;
};

struct SigmaEstimate {
  double sigma = 0;
  EstimateBound bound = EstimateBound::interpolated;
};

struct SigmaEstimates {
  std::string method;  ///< the conditions' method: the first word of their label
  double threshold = 4.0;
  std::vector<LevelScore> levels;  ///< mean score per (sigma_d, sigma_nd), ascending
  /// From the uniform levels (sigma_d == sigma_nd); none when no uniform level was scored.
  std::optional<SigmaEstimate> sigma_uf;
  /// From the levels whose sigma_d is the largest tested one at or below sigma_UF (the
  /// smallest when none is), over sigma_nd; none without sigma_UF or such levels.
  std::optional<SigmaEstimate> sigma_nf;
  double sigma_nf_at_sigma_d = 0;
};

/// Per method (in order of first appearance), over the score trials that carry sigma_d
/// and sigma_nd. `threshold` in (1, 5].
std::vector<SigmaEstimates> estimate_sigmas(std::span<const ScoreTrial> trials, double threshold);

}  // namespace foveal

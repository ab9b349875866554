#pragma once
// Per-pair votes with the exact binomial test, and mean scores (docs/study.md).
#include <cstdint>
#include <string>
#include <vector>

#include "foveal/study/sigma_estimates.hpp"
#include "foveal/study/study_trials.hpp"

namespace foveal {

/// One unordered pair of conditions, `first` being the one met first in the file.
struct PairVotes {
  std::string first, second;
  std::uint64_t trials = 0;
  std::uint64_t votes_first = 0, votes_second = 0;
  double share_first = 0;  ///< votes_first / trials
  double p_value = 1;      ///< two-sided exact binomial test against 0.5
};

struct ConditionScore {
  std::string condition;
  std::uint64_t trials = 0;
  double mean = 0;
  double sd = 0;  ///< sample standard deviation (n - 1); 0 for one trial
};

struct StudyStats {
  std::vector<PairVotes> pairs;        ///< in order of first appearance
  std::vector<ConditionScore> scores;  ///< in order of first appearance
  std::uint64_t validation_trials = 0;
  std::vector<SigmaEstimates> sigmas;  ///< per method, from the score trials with sigma_d, sigma_nd
};

/// `score_threshold`: the mean score that still counts as "no visible difference" for
/// the sigma_UF / sigma_NF estimates, in (1, 5].
StudyStats compute_study_stats(const StudyTrials& trials, double score_threshold = 4.0);

}  // namespace foveal

#pragma once
// The trials CSV of a user study (docs/study.md): one row per trial, columns by name.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "foveal/core/error.hpp"

namespace foveal {

/// A two-alternative forced choice between the conditions shown as `a` and `b`.
struct ChoiceTrial {
  std::string condition_a, condition_b;  ///< method, with the other `*_a`/`*_b` columns
  bool chose_a = false;
  std::uint64_t line = 0;
};

/// A rating of one condition, 1 (worst) to 5 (best).
struct ScoreTrial {
  std::string condition;
  int score = 0;
  std::uint64_t line = 0;
  /// The optional `sigma_d`, `sigma_nd` columns: the levels scored (for sigma_UF/sigma_NF).
  std::optional<double> sigma_d, sigma_nd;
};

struct StudyTrials {
  std::vector<ChoiceTrial> choices;
  std::vector<ScoreTrial> scores;
  std::uint64_t validation_trials = 0;  ///< rows flagged `validation`, left out of both
};

/// Reads the whole file; the first bad row is an error naming file:line: column.
Result<StudyTrials> read_study_trials(const std::string& path);

}  // namespace foveal

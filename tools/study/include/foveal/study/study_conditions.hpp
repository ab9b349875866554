#pragma once
// The per-condition file `study run` writes beside its trials (conditions.csv: each
// condition's predicted JOD, docs/study.md "Predicted JOD"), read back so `study stats`
// can print the prediction beside the observed votes and scores.
#include <map>
#include <string>

#include "foveal/core/error.hpp"

namespace foveal {

struct PredictedJod {
  double jod = 0, left = 0, right = 0;  ///< means over the file's scenes
  int scenes = 0;
};

/// Condition label -> its predicted JOD. Each row is filed under both labels a condition
/// has in the statistics: its `condition` column (a score trial's label) and, for a
/// uniform condition (sigma_nd = sigma_d or no sigma_nd column), the 2AFC form `study
/// stats` builds from method_a, sigma_a, f_a ("rmfr sigma=2.6 f=0.3", "full sigma=1 f=").
/// Needs the columns condition, method, sigma_d, f and predicted_jod (sigma_nd,
/// predicted_jod_left/_right optional); errors name file:line: column.
Result<std::map<std::string, PredictedJod>> read_predicted_jod(const std::string& path);

}  // namespace foveal

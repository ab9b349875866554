#pragma once
// `foveal predict-eval`'s report of evaluate_prediction's results: JSON, the text tables,
// and the latencies that no sample could score.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/evaluation/prediction_eval.hpp"

namespace foveal::evaluation {

/// Per latency, per truth, phase and what was shown: n and the p50/p95/p99/mean error in
/// degrees (null where no sample was scored).
nlohmann::json results_json(const std::vector<LatencyResult>& rs);

/// The same as text tables, one per truth.
void print_results(const std::vector<LatencyResult>& rs);

/// "3, 40 ms": the latencies at which not one sample could be scored; empty when none.
std::string unevaluated(const std::vector<LatencyResult>& rs);

}  // namespace foveal::evaluation

#include "foveal/evaluation/prediction_report.hpp"

#include <cstdio>

#include "foveal/core/shown_text.hpp"

namespace foveal::evaluation {

nlohmann::json results_json(const std::vector<LatencyResult>& rs) {
  nlohmann::json out = nlohmann::json::array();
  for (const LatencyResult& r : rs) {
    nlohmann::json by_truth;
    for (Truth tr : kTruths) {
      nlohmann::json by_phase;
      for (Phase ph : kPhases) {
        nlohmann::json by_shown;
        for (Shown s : kShown) {
          const ErrorStats& e = r.stats[static_cast<std::size_t>(tr)][static_cast<std::size_t>(ph)][static_cast<std::size_t>(s)];
          // No sample, no figure: null, never a 0° error nobody measured.
          const auto deg = [&e](double v) { return e.n ? nlohmann::json(v) : nlohmann::json(nullptr); };
          by_shown[shown_name(s)] = {{"n", e.n}, {"p50_deg", deg(e.p50)}, {"p95_deg", deg(e.p95)}, {"p99_deg", deg(e.p99)}, {"mean_deg", deg(e.mean)}};
        }
        by_phase[phase_name(ph)] = by_shown;
      }
      by_truth[truth_name(tr)] = by_phase;
    }
    out.push_back({{"latency_ms", r.latency_ms}, {"truth", by_truth}});
  }
  return out;
}

void print_results(const std::vector<LatencyResult>& rs) {
  for (Truth tr : kTruths) {
    std::printf("truth: %s\n", tr == Truth::recorded ? "the recorded gaze at t+L (interpolated; its noise is in every column)"
                                                     : "a centred 5-sample mean of the recorded gaze at t+L (no lag, blurs saccades)");
    for (const LatencyResult& r : rs) {
      std::printf("  L = %g ms, error p50/p95/p99 (deg)\n  %-14s %6s", r.latency_ms, "at t+L", "n");
      for (Shown s : kShown) std::printf("  %-20s", shown_name(s));
      std::printf("\n");
      for (Phase ph : kPhases) {
        const auto& row = r.stats[static_cast<std::size_t>(tr)][static_cast<std::size_t>(ph)];
        std::printf("  %-14s %6zu", phase_name(ph), row[0].n);
        for (const ErrorStats& e : row)
          if (e.n) std::printf("  %5.2f/%5.2f/%6.2f   ", e.p50, e.p95, e.p99);
          else std::printf("  %-20s", "    -/    -/     -");
        std::printf("\n");
      }
    }
  }
}

// The latencies at which not one sample could be scored (no valid eye at t with a truth
// at t + L): figures there would be made up.
std::string unevaluated(const std::vector<LatencyResult>& rs) {
  std::string out;
  for (const LatencyResult& r : rs)
    if (r.stats[static_cast<std::size_t>(Truth::recorded)][static_cast<std::size_t>(Phase::all)][0].n == 0)
      out += (out.empty() ? "" : ", ") + shown_number(r.latency_ms) + " ms";
  return out;
}

}  // namespace foveal::evaluation

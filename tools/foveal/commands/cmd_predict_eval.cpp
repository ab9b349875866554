// `foveal predict-eval`: angular error at display time with and without prediction
// (docs/results/latency/prediction.md).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>

#include "commands.hpp"
#include "commands/filter_args.hpp"
#include "foveal/core/gaze_log.hpp"
#include "foveal/core/json_file.hpp"
#include "foveal/core/shown_text.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/runtime/profile.hpp"
#include "foveal/evaluation/prediction_eval.hpp"
#include "foveal/evaluation/prediction_report.hpp"

namespace foveal::cmd {

namespace {

// The most latencies one run evaluates: each keeps every sample's errors (a run with
// 3,000 of them took 2.6 GB).
constexpr std::size_t kMaxLatencies = 32;

}  // namespace

void add_predict_eval(CLI::App& app, int& exit_code) {
  struct Args {
    std::vector<std::string> logs;
    std::string config, profile, display;
    std::vector<double> latencies_ms{11, 22, 45};
    double max_horizon_ms = -1;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "predict-eval",
      "Angular error at display time t+L against the recorded gaze at t+L: the raw sample, the filter, the filter "
      "with predict_ms = L, and predict_fovea (docs/results/latency/prediction.md)");
  sub->add_option("logs", a->logs, "Native gaze logs (several are pooled)")->required();
  sub->add_option("--latency-ms", a->latencies_ms, "Latencies to evaluate, comma-separated (0 < L <= 200, at most 32)")
      ->delimiter(',')
      ->capture_default_str();
  sub->add_option("--config", a->config, "Filter settings JSON (keys of docs/filtering.md)");
  sub->add_option("--profile", a->profile, "Take the filter settings from this profile");
  sub->add_option("--display", a->display, "Display model: a name under data/display (htc_vive_pro_eye, hires_3800_35ppd) or a JSON file (default: htc_vive_pro_eye)");
  sub->add_option("--max-horizon-ms", a->max_horizon_ms, "predict_fovea's horizon clamp (default: FoveaPrediction's)");
  sub->add_flag("--json", a->json, "Print the figures as JSON (per log and pooled)");
  sub->callback([a, &exit_code] {
    auto fail = [&exit_code](const Error& e) { exit_code = cli::report(e); };
    if (a->latencies_ms.empty()) return fail(bad_input("predict-eval: --latency-ms: give at least one latency"));
    if (a->latencies_ms.size() > kMaxLatencies)
      return fail(bad_input("predict-eval: --latency-ms: " + std::to_string(a->latencies_ms.size()) + " latencies, at most " +
                            std::to_string(kMaxLatencies) + " in one run"));
    for (double L : a->latencies_ms)
      if (!(L > 0 && L <= 200))
        return fail(bad_input("predict-eval: --latency-ms: " + shown_number(L) + " is not in (0, 200]"));
    FoveaPrediction pred;
    if (a->max_horizon_ms != -1) {
      if (!(a->max_horizon_ms >= 0 && a->max_horizon_ms <= 1000))
        return fail(bad_input("predict-eval: --max-horizon-ms: " + shown_number(a->max_horizon_ms) +
                              " is not in [0, 1000]"));
      pred.max_horizon_ns = static_cast<TimeNs>(std::llround(a->max_horizon_ms * 1e6));
    }
    auto cfg_or = filter_config_from(a->config, a->profile, "predict-eval");
    if (!cfg_or) return fail(cfg_or.error());
    const FilterConfig cfg = *cfg_or;
    auto model_or = display_model_from(a->display);
    if (!model_or) return fail(model_or.error());
    const DisplayModel model = *model_or;
    // Every log is read before anything is printed: a bad one leaves no partial output.
    std::vector<std::vector<GazeSample>> logs;
    for (const std::string& path : a->logs) {
      auto s = read_gaze_log(path);
      if (!s) return fail(s.error());
      if (s->size() < 2) return fail(bad_input(path + ": fewer than 2 samples, nothing to evaluate"));
      logs.push_back(std::move(*s));
    }
    evaluation::PredictionEvaluator pooled(model, cfg, a->latencies_ms, pred);
    nlohmann::json per_log = nlohmann::json::array();
    for (std::size_t i = 0; i < logs.size(); ++i) {
      pooled.add(logs[i]);
      if (a->json)
        per_log.push_back({{"log", a->logs[i]},
                           {"samples", logs[i].size()},
                           {"latencies", evaluation::results_json(evaluation::evaluate_prediction(logs[i], model, cfg, a->latencies_ms, pred))}});
    }
    const auto all = pooled.result();
    // Nothing evaluated is bad input, not a 0° error (docs/filtering.md).
    if (const std::string none = evaluation::unevaluated(all); !none.empty())
      return fail(bad_input("predict-eval: no sample could be evaluated at L = " + none + ": none of the " +
                            std::to_string(logs.size()) + " log(s) has a valid eye at t with a recorded gaze at t + L "
                            "(every sample invalid, or the valid runs shorter than L)"));
    if (a->json) {
      cli::print_json({{"logs", per_log},
                       {"pooled", evaluation::results_json(all)},
                       {"max_horizon_ms", static_cast<double>(pred.max_horizon_ns) / 1e6},
                       {"display", model.name}});
      return;
    }
    std::size_t samples = 0;
    for (const auto& l : logs) samples += l.size();
    std::printf("%zu log(s), %zu samples, both eyes pooled; predict_fovea max horizon %g ms\n", logs.size(), samples,
                static_cast<double>(pred.max_horizon_ns) / 1e6);
    evaluation::print_results(all);
  });
}

}  // namespace foveal::cmd

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "commands.hpp"
#include "commands/filter_args.hpp"
#include "foveal/core/atomic_file.hpp"
#include "foveal/core/gaze_log.hpp"
#include "foveal/core/json_file.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/runtime/fovea_trace.hpp"
#include "foveal/runtime/gaze_pipeline.hpp"
#include "foveal/runtime/latency_histogram.hpp"
#include "foveal/runtime/profile.hpp"

namespace foveal::cmd {

void add_replay(CLI::App& app, int& exit_code) {
  struct Args {
    std::string log, trace, config, profile, display;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("replay", "Run a gaze log through the gaze pipeline as fast as possible");
  sub->add_option("log", a->log, "Native gaze log")->required();
  sub->add_option("--trace", a->trace, "Per-sample trace CSV (time, state, fovea per eye, confidence)");
  sub->add_option("--config", a->config, "Filter settings JSON (keys of docs/filtering.md)");
  sub->add_option("--profile", a->profile, "Take the filter settings from this profile");
  sub->add_option("--display", a->display, "Display model: a name under data/display (htc_vive_pro_eye, hires_3800_35ppd) or a JSON file (default: htc_vive_pro_eye)");
  sub->add_flag("--json", a->json, "Print the summary as JSON");
  sub->callback([a, &exit_code] {
    auto fail = [&exit_code](const Error& e) { exit_code = cli::report(e); };
    auto cfg_or = filter_config_from(a->config, a->profile, "replay");
    if (!cfg_or) return fail(cfg_or.error());
    FilterConfig cfg = *cfg_or;
    auto model_or = display_model_from(a->display);
    if (!model_or) return fail(model_or.error());
    const DisplayModel model = *model_or;
    auto reader = GazeLogReader::open(a->log);
    if (!reader) return fail(reader.error());
    std::optional<cli::FoveaTrace> trace;
    if (!a->trace.empty()) {
      const std::string profile_file = a->profile.empty() ? "" : ProfileStore::user().path_of(a->profile);
      if (Status st = check_output_is_not_an_input(a->trace, {a->log, a->config, profile_file, a->display}); !st)
        return fail(st.error());
      auto t = cli::FoveaTrace::create(a->trace);
      if (!t) return fail(t.error());
      trace.emplace(std::move(t.value()));
    }
    GazePipeline pipe(model, cfg);
    LatencyHistogram cost;
    std::uint64_t samples = 0, saccades[2] = {0, 0}, fixations[2] = {0, 0}, blinks[2] = {0, 0};
    double lost_ms[2] = {0, 0};
    FoveaState prev[2] = {FoveaState::lost, FoveaState::lost};
    TimeNs t0 = 0, prev_t = 0;
    double cost_sum_ns = 0;
    GazeSample s;
    for (;;) {
      auto got = reader->next(s);
      if (!got) return fail(got.error());
      if (!*got) break;
      const TimeNs c0 = monotonic_now_ns();
      const FoveaFrame f = pipe.update(s);
      const TimeNs c = monotonic_now_ns() - c0;
      cost.add(c);
      cost_sum_ns += static_cast<double>(c);
      if (samples == 0) t0 = s.t_ns;
      for (int e = 0; e < 2; ++e) {
        const FoveaState st = f.eyes[e].state;
        saccades[e] += pipe.events(static_cast<Eye>(e)).saccade_onset;
        if (st != prev[e]) {
          fixations[e] += st == FoveaState::fixation;
          blinks[e] += st == FoveaState::blink;
        }
        if (st == FoveaState::lost && samples > 0) lost_ms[e] += static_cast<double>(s.t_ns - prev_t) / 1e6;
        prev[e] = st;
      }
      if (trace) trace->write(f);
      prev_t = s.t_ns;
      ++samples;
    }
    if (trace)
      if (Status st = trace->commit(); !st) return fail(st.error());
    nlohmann::json eyes;
    for (int e = 0; e < 2; ++e)
      eyes[eye_name(static_cast<Eye>(e))] = {{"fixations", fixations[e]}, {"saccades", saccades[e]},
                                             {"blinks", blinks[e]}, {"time_lost_ms", lost_ms[e]}};
    const nlohmann::json j = {{"log", a->log},
                              {"samples", samples},
                              {"duration_s", static_cast<double>(prev_t - t0) / 1e9},
                              {"eyes", eyes},
                              {"cost_ns_per_sample", {{"mean", samples ? cost_sum_ns / static_cast<double>(samples) : 0.0},
                                                      {"p99", cost.percentile(0.99)}}},
                              {"trace", a->trace}};
    if (a->json) {
      cli::print_json(j);
      return;
    }
    std::printf("%s: %llu samples, %.2f s\n", a->log.c_str(), static_cast<unsigned long long>(samples),
                j["duration_s"].get<double>());
    for (int e = 0; e < 2; ++e)
      std::printf("  %-5s fixations %4llu  saccades %4llu  blinks %3llu  time lost %7.1f ms\n", eye_name(static_cast<Eye>(e)),
                  static_cast<unsigned long long>(fixations[e]), static_cast<unsigned long long>(saccades[e]),
                  static_cast<unsigned long long>(blinks[e]), lost_ms[e]);
    std::printf("  cost per sample: mean %.0f ns, p99 %lld ns (timer overhead included)\n",
                j["cost_ns_per_sample"]["mean"].get<double>(), static_cast<long long>(cost.percentile(0.99)));
  });
}

}  // namespace foveal::cmd

// `foveal log quality`: the data-quality measures of docs/quality.md for a gaze log.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "foveal/core/gaze_log.hpp"
#include "foveal/quality/gaze_quality.hpp"
#include "foveal/quality/quality_targets.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/evaluation/quality_report.hpp"

namespace foveal::cmd {

void add_log_quality(CLI::App& log, int& exit_code) {
  struct Args {
    std::string file, targets;
    std::optional<double> start_s, end_s;
    std::vector<std::string> between;
    bool json = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub = log.add_subcommand(
      "quality", "Data quality per eye and binocular: accuracy, RMS-S2S, STD, BCEA, data loss, effective frequency");
  sub->add_option("file", args->file, "Native gaze log")->required();
  sub->add_option("--start", args->start_s, "Window start, seconds from the first sample");
  sub->add_option("--end", args->end_s, "Window end, seconds from the first sample");
  sub->add_option("--between", args->between, "Window from marker MARK1 to the next marker MARK2")
      ->expected(2)
      ->excludes("--start")
      ->excludes("--end");
  sub->add_option("--targets", args->targets, "Targets CSV (start_s,end_s,azimuth_deg,elevation_deg) for accuracy");
  sub->add_flag("--json", args->json, "Print the report as JSON");
  sub->callback([args, &exit_code] {
    QualityOptions options{args->start_s, args->end_s, {}};
    if (!args->targets.empty()) {
      auto t = read_quality_targets(args->targets);
      if (!t) {
        exit_code = cli::report(t.error());
        return;
      }
      options.targets = std::move(t.value());
    }
    GazeLogHeader header;
    std::vector<GazeMarker> markers;
    auto samples = read_gaze_log(args->file, &header, &markers);
    if (!samples) {
      exit_code = cli::report(samples.error());
      return;
    }
    if (!args->between.empty()) {
      auto w = window_between_markers(*samples, markers, args->between[0], args->between[1]);
      if (!w) {
        exit_code = cli::report(Error{w.error().kind, args->file + ": " + w.error().message});
        return;
      }
      options.start_s = w->start_s;
      options.end_s = w->end_s;
    }
    auto q = compute_gaze_quality(*samples, header.rate_hz, options);
    if (!q) {
      exit_code = cli::report(Error{q.error().kind, args->file + ": " + q.error().message});
      return;
    }
    if (args->json) cli::print_json(evaluation::quality_json(args->file, *q));
    else evaluation::print_quality_text(args->file, *q);
  });
}

}  // namespace foveal::cmd

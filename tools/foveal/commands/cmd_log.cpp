#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>

#include "commands.hpp"
#include "foveal/core/gaze_log_stats.hpp"
#include "foveal/runtime/cli.hpp"

namespace foveal::cmd {

namespace {

nlohmann::json stats_json(const std::string& path, const GazeLogStats& s) {
  nlohmann::json runs = nlohmann::json::array();
  for (const InvalidRun& r : s.invalid_runs)
    runs.push_back({{"first_sample", r.first_index}, {"samples", r.samples}, {"start_s", r.start_s},
                    {"duration_ms", r.duration_ms}, {"kind", r.kind}, {"at_end", r.at_end}});
  return {{"file", path},
          {"format_version", s.header.version},
          {"nominal_rate_hz", s.header.rate_hz},
          {"meta", s.header.meta},
          {"samples", s.samples},
          {"duration_s", s.duration_s},
          {"estimated_rate_hz", s.estimated_rate_hz},
          {"median_interval_ms", s.median_interval_ms},
          {"invalid_pct", {{"left", s.invalid_pct[0]}, {"right", s.invalid_pct[1]}}},
          {"longest_gap_ms", s.longest_gap_ms},
          {"longest_gap_at_s", s.longest_gap_at_s},
          {"blinks", s.blinks},
          {"invalid_runs", runs},
          {"head_pose", {{"samples", s.head_pose_samples}, {"max_turn_deg", s.head_max_turn_deg},
                         {"max_travel_m", s.head_max_travel_m}}}};
}

void print_text(const std::string& path, const GazeLogStats& s) {
  std::printf("%s: valid gaze log v%d\n", path.c_str(), s.header.version);
  std::printf("  samples            %llu\n", static_cast<unsigned long long>(s.samples));
  std::printf("  duration           %.3f s\n", s.duration_s);
  std::printf("  rate               %.2f Hz estimated (%.6g Hz nominal, median interval %.2f ms)\n",
              s.estimated_rate_hz, s.header.rate_hz, s.median_interval_ms);
  std::printf("  invalid            left %.2f%%, right %.2f%%\n", s.invalid_pct[0], s.invalid_pct[1]);
  std::printf("  longest gap        %.2f ms at %.3f s\n", s.longest_gap_ms, s.longest_gap_at_s);
  if (s.header.has_head_pose())
    std::printf("  head pose          %llu samples; at most %.1f deg and %.3f m from the first\n",
                static_cast<unsigned long long>(s.head_pose_samples), s.head_max_turn_deg, s.head_max_travel_m);
  std::printf("  invalid runs       %zu (%llu blink-like)\n", s.invalid_runs.size(),
              static_cast<unsigned long long>(s.blinks));
  // In time order, capped: --json has them all.
  constexpr std::size_t kMaxListed = 20;
  for (std::size_t i = 0; i < s.invalid_runs.size() && i < kMaxListed; ++i) {
    const InvalidRun& r = s.invalid_runs[i];
    std::printf("    %-8s at %8.3f s  %4llu samples  %8.1f ms%s\n", r.kind.c_str(), r.start_s,
                static_cast<unsigned long long>(r.samples), r.duration_ms, r.at_end ? "  (until the end)" : "");
  }
  if (s.invalid_runs.size() > kMaxListed)
    std::printf("    ... %zu more (--json lists all)\n", s.invalid_runs.size() - kMaxListed);
}

}  // namespace

void add_log(CLI::App& app, int& exit_code) {
  CLI::App* log = app.add_subcommand("log", "Inspect native gaze logs (and plot them or a fovea trace)");
  log->require_subcommand(1);
  struct Args {
    std::string file;
    bool json = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* validate = log->add_subcommand("validate", "Check a gaze log and report its statistics");
  validate->add_option("file", args->file, "Native gaze log")->required();
  validate->add_flag("--json", args->json, "Print the report as JSON");
  validate->callback([args, &exit_code] {
    auto s = compute_gaze_log_stats(args->file);
    if (!s) {
      exit_code = cli::report(s.error());
      return;
    }
    if (args->json) cli::print_json(stats_json(args->file, *s));
    else print_text(args->file, *s);
  });
  add_log_quality(*log, exit_code);
  add_log_plot(*log, exit_code);
}

}  // namespace foveal::cmd

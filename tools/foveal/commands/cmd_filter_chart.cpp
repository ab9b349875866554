#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>

#include "commands.hpp"
#include "foveal/core/data_paths.hpp"
#include "foveal/core/gaze_log.hpp"
#include "foveal/core/json_text.hpp"
#include "foveal/import/importers.hpp"
#include "foveal/tools/filter_score.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/tools/run_program.hpp"
#include "foveal/tools/staged_outputs.hpp"

namespace foveal::cmd {

namespace {

struct Variant {
  std::string method, label;
  FilterConfig cfg;
  bool raw = false;
};

std::vector<Variant> variants() {
  std::vector<Variant> v;
  v.push_back({"none", "no filter", {}, true});
  for (auto [mc, beta] : {std::pair{0.3, 0.0}, {1.0, 0.0}, {1.0, 0.1}, {2.0, 0.1}, {4.0, 0.3}, {8.0, 0.5}}) {
    FilterConfig c;
    c.saccade_aware = false;
    c.one_euro = {mc, beta, 1.0};
    std::ostringstream l;
    l << "1euro mc=" << mc << " b=" << beta;
    v.push_back({"one_euro", l.str(), c});
  }
  for (double mc : {0.1, 0.3, 1.0, 2.0}) {
    FilterConfig c;
    c.one_euro.min_cutoff_hz = mc;
    std::ostringstream l;
    l << "saccade-aware mc=" << mc;
    v.push_back({"saccade_aware", l.str(), c});
  }
  return v;
}

// Real data has no truth: jitter is the RMS distance of the output from its own
// 100 ms centred mean (±`half` samples at the log's rate) over runs the pipeline calls
// fixation. None when no such run exists (a chart shows no bar, not a jitter of 0).
std::optional<double> real_jitter_deg(const std::vector<GazeSample>& samples, const FilterConfig& cfg, bool raw, std::size_t half) {
  GazePipeline pipe(DisplayModel::vive_pro_eye(), cfg);
  std::vector<std::pair<glm::vec3, bool>> out;
  for (const GazeSample& s : samples) {
    const FoveaFrame f = pipe.update(s);
    const bool fix = f.eyes[0].state == FoveaState::fixation;
    out.emplace_back(raw ? s.eyes[0].direction : pipe.events(Eye::left).direction(), fix && s.eyes[0].has(kValidDirection));
  }
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t i = half; i + half < out.size(); ++i) {
    bool all = true;
    glm::vec3 mean{0.0f};
    for (std::size_t k = i - half; k <= i + half; ++k) {
      all &= out[k].second;
      mean += out[k].first;
    }
    if (!all) continue;
    mean /= static_cast<float>(2 * half + 1);
    const glm::vec3 d = out[i].first - mean;
    sum += static_cast<double>(d.x * d.x + d.y * d.y + d.z * d.z);
    ++n;
  }
  if (n == 0) return std::nullopt;
  return std::sqrt(sum / static_cast<double>(n)) * 180.0 / 3.14159265358979;
}

// A recording to chart jitter on: a SRanipal export (imported on the fly) or a native log.
struct Recording {
  std::filesystem::path path;
  const char* source;  ///< "SRanipal" or "log": the chart's legend says which
};

}  // namespace

void add_filter_chart(CLI::App& app, int& exit_code) {
  struct Args {
    std::string out = "filter-chart";
    // The three recordings foveal ships (data/gaze/vive_pro_eye/SOURCE.md).
    std::string vive_dir = data_path("data/gaze/vive_pro_eye");
    std::vector<std::string> logs;
    double seconds = 120;
    bool json = false, no_png = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("filter-chart", "Chart jitter against lag for no filter, 1€ presets and the saccade-aware pipeline");
  sub->add_option("--out,-o", a->out, "Output directory (CSV, JSON, PNG)")->capture_default_str();
  CLI::Option* vive = sub->add_option("--vive-dir", a->vive_dir, "Folder of SRanipal recordings to chart jitter on (imported on the fly)")
                          ->capture_default_str();
  sub->add_option("--log", a->logs, "Native gaze log to chart jitter on (repeatable; `foveal import`, `record`); "
                                    "with --log the SRanipal folder is charted only when --vive-dir is given");
  sub->add_option("--seconds", a->seconds, "Synthetic scanpath length per seed")->capture_default_str();
  sub->add_flag("--no-png", a->no_png, "Write the data only (no matplotlib)");
  sub->add_flag("--json", a->json, "Print the results as JSON");
  sub->callback([a, vive, &exit_code] {
    auto fail = [&exit_code](const Error& e) { exit_code = cli::report(e); };
    // A missing or empty folder is refused up front: a chart without its real-data half
    // would look complete.
    std::vector<Recording> recordings;
    if (a->logs.empty() || vive->count() > 0) {
      std::error_code dir_ec;
      for (std::filesystem::directory_iterator it(a->vive_dir, dir_ec), end; !dir_ec && it != end; it.increment(dir_ec))
        if (it->path().extension() == ".csv") recordings.push_back({it->path(), "SRanipal"});
      if (dir_ec) return fail(bad_input("--vive-dir " + a->vive_dir + ": " + dir_ec.message()));
      if (recordings.empty()) return fail(bad_input("--vive-dir " + a->vive_dir + ": no .csv recordings in it"));
      std::sort(recordings.begin(), recordings.end(), [](const Recording& x, const Recording& y) { return x.path < y.path; });
    }
    // The logs are read now, before any work: a bad row fails the run at once, naming file and line.
    std::vector<std::pair<std::vector<GazeSample>, GazeLogHeader>> log_samples;
    for (const std::string& log : a->logs) {
      GazeLogHeader header;
      auto samples = read_gaze_log(log, &header);
      if (!samples) return fail(samples.error());
      recordings.push_back({log, "log"});
      log_samples.emplace_back(std::move(*samples), header);
    }
    // Every output is staged and moved into --out together at the end (or not at all).
    auto staged = cli::StagedOutputs::create(a->out);
    if (!staged) return fail(staged.error());
    std::error_code ec;
    const auto vs = variants();
    std::string csv = "method,label,min_cutoff_hz,beta,jitter_deg,step_lag_ms,pursuit_lag_ms,onset_f1\n";
    nlohmann::json results = nlohmann::json::array();
    cli::Progress progress("filter-chart", vs.size(), !a->json);
    std::size_t done = 0;
    for (const Variant& v : vs) {
      FilterScore avg;
      const int seeds = 3;
      for (int seed = 1; seed <= seeds; ++seed) {
        SyntheticOptions o;
        o.seed = static_cast<std::uint64_t>(seed);
        o.duration_s = a->seconds;
        const FilterScore s = score_pipeline(o, v.cfg, 50.0, v.raw);
        avg.filtered_fixation_rms_deg += s.filtered_fixation_rms_deg / seeds;
        avg.mean_fixation_lag_ms += s.mean_fixation_lag_ms / seeds;
        avg.pursuit_lag_ms += s.pursuit_lag_ms / seeds;
        avg.onset_f1 += s.onset_f1 / seeds;
      }
      char row[256];
      std::snprintf(row, sizeof row, "%s,%s,%g,%g,%.4f,%.2f,%.2f,%.3f\n", v.method.c_str(), v.label.c_str(),
                    v.cfg.one_euro.min_cutoff_hz, v.cfg.one_euro.beta, avg.filtered_fixation_rms_deg,
                    avg.mean_fixation_lag_ms, avg.pursuit_lag_ms, v.raw ? 0.0 : avg.onset_f1);
      csv += row;
      results.push_back({{"method", v.method}, {"label", v.label}, {"jitter_deg", avg.filtered_fixation_rms_deg},
                         {"step_lag_ms", avg.mean_fixation_lag_ms}, {"pursuit_lag_ms", avg.pursuit_lag_ms}});
      progress.update(++done);
    }
    progress.finish();
    // Real recordings: jitter only.
    // jitter_deg is empty where the recording has no fixation run long enough.
    std::string real_csv = "recording,method,label,jitter_deg,source\n";
    std::size_t next_log = 0;
    for (const Recording& rec : recordings) {
      std::vector<GazeSample> samples;
      GazeLogHeader header;
      if (rec.source == std::string("log")) {
        samples = std::move(log_samples[next_log].first);
        header = log_samples[next_log++].second;
      } else {
        const std::string tmp = staged->staging() + "/.import.csv";
        if (auto imp = import_sranipal(rec.path.string(), tmp); !imp) return fail(imp.error());
        auto read = read_gaze_log(tmp, &header);
        std::filesystem::remove(tmp, ec);
        if (!read) return fail(read.error());
        samples = std::move(*read);
      }
      // ±50 ms: 6 samples at the Vive Pro Eye's 120 Hz, at least one at any rate.
      const auto half = static_cast<std::size_t>(std::max(1.0, std::round(0.05 * header.rate_hz)));
      // A name with a comma or quote would split the row: such characters become '_'.
      std::string name = rec.path.stem().string();
      std::replace_if(name.begin(), name.end(), [](char c) { return c == ',' || c == '"' || c == '\n' || c == '\r'; }, '_');
      for (const Variant& v : vs) {
        const std::optional<double> j = real_jitter_deg(samples, v.cfg, v.raw, half);
        real_csv += name + "," + v.method + "," + v.label + "," + (j ? std::to_string(*j) : "") + "," + rec.source + "\n";
      }
    }
    if (Status s = staged->write("filter_chart.csv", csv); !s) return fail(s.error());
    if (Status s = staged->write("filter_chart_real.csv", real_csv); !s) return fail(s.error());
    if (Status s = staged->write("filter_chart.json", json_text(results, 2) + "\n"); !s) return fail(s.error());
    if (!a->no_png) {
      // No shell: --out reaches the script as one argument whatever characters it holds.
      const std::string python = "/usr/bin/python3", script = data_path("tools/charts/filter_chart.py");
      auto r = cli::run_program({python, script, staged->staging()});
      if (!r) return fail(r.error());
      if (!r->ok())
        return fail(io_error("charts: " + python + " " + script + " ended with " + cli::describe_end(*r) +
                             " (its message is above); nothing was written"));
    }
    if (auto moved = staged->commit(); !moved) return fail(moved.error());
    if (a->json) cli::print_json({{"synthetic", results}, {"out", a->out}});
    else std::printf("wrote %s/filter_chart.{csv,json,png} and filter_chart_real.csv\n", a->out.c_str());
  });
}

}  // namespace foveal::cmd

// foveald: the runtime daemon. For now it replays a gaze log (the bundled real Vive Pro
// Eye recording by default) through the runtime and writes the per-eye fovea trace and a
// summary; the compositor and the threaded daemon loop build on this.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "foveal/core/atomic_file.hpp"
#include "foveal/core/data_paths.hpp"
#include "foveal/drivers/replay_source.hpp"
#include "foveal/runtime/fovea.hpp"
#include "foveal/tools/cli.hpp"

namespace {

constexpr const char* kDefaultLog = "data/gaze/vive_pro_eye_TESTNA01.csv";

struct Options {
  std::string replay;
  std::string display;
  std::string out = "foveald-out";
  double speed = 1.0;
  bool loop = false;
  bool headless = true;
  bool json = false;
  bool quiet = false;
  std::optional<double> start_s, end_s;
};

double percentile(std::vector<double>& v, double p) {
  if (v.empty()) return 0;
  const auto k = static_cast<std::size_t>(p * static_cast<double>(v.size() - 1) + 0.5);
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

int run(const Options& o) {
  using namespace foveal;
  DisplayModel model = DisplayModel::vive_pro_eye();
  if (!o.display.empty()) {
    auto m = DisplayModel::load(o.display);
    if (!m) return cli::report(m.error(), "foveald");
    model = *m;
  }
  ReplayOptions ro;
  ro.path = o.replay.empty() ? data_path(kDefaultLog) : o.replay;
  ro.speed = o.speed;
  ro.loop = o.loop;
  ro.start_s = o.start_s;
  ro.end_s = o.end_s;
  if (o.loop && !o.end_s) return cli::report(bad_input("--loop needs --end (a looping replay never ends)"), "foveald");
  ReplaySource source(ro);
  if (Status s = source.open(); !s) return cli::report(s.error(), "foveald");

  std::error_code ec;
  std::filesystem::create_directories(o.out, ec);
  if (ec) return cli::report(io_error(o.out + ": cannot create output directory: " + ec.message()), "foveald");
  auto trace = AtomicFile::create(o.out + "/trace.csv");
  if (!trace) return cli::report(trace.error(), "foveald");
  trace->write("t_ns,left_state,left_x_px,left_y_px,left_confidence,right_state,right_x_px,right_y_px,right_confidence\n");

  if (Status s = source.start(); !s) return cli::report(s.error(), "foveald");
  RawFoveaMapper mapper(model);
  std::vector<double> lateness_ms;  // delivery time minus due time
  std::size_t worst_index = 0;
  std::uint64_t samples = 0, state_counts[2][5] = {};
  TimeNs first_t = 0, last_t = 0;
  const TimeNs wall0 = monotonic_now_ns();
  for (;;) {
    ReadResult r = source.next(std::chrono::milliseconds(100));
    if (r.status == ReadStatus::timeout) continue;
    if (r.status == ReadStatus::end) break;
    if (r.status != ReadStatus::sample) return cli::report(r.error, "foveald");
    const TimeNs now = monotonic_now_ns();
    if (o.speed > 0) {
      lateness_ms.push_back(static_cast<double>(now - r.sample.t_ns) / 1e6);
      if (lateness_ms.back() > lateness_ms[worst_index]) worst_index = lateness_ms.size() - 1;
    }
    const FoveaFrame f = mapper.update(r.sample);
    if (samples == 0) first_t = f.t_ns;
    last_t = f.t_ns;
    char row[256];
    const FoveaPoint &l = f.eye(Eye::left), &rr = f.eye(Eye::right);
    const int n = std::snprintf(row, sizeof row, "%lld,%s,%.3f,%.3f,%.2f,%s,%.3f,%.3f,%.2f\n",
                                static_cast<long long>(f.t_ns - first_t), fovea_state_name(l.state), l.px.x, l.px.y,
                                l.confidence, fovea_state_name(rr.state), rr.px.x, rr.px.y, rr.confidence);
    trace->write(std::string_view(row, static_cast<std::size_t>(n)));
    ++state_counts[0][static_cast<int>(l.state)];
    ++state_counts[1][static_cast<int>(rr.state)];
    ++samples;
    if (!o.quiet && !o.json && (samples % 120) == 0) {
      std::fprintf(stderr, "\rfoveald: %llu samples, %.1f s  L(%.0f,%.0f) R(%.0f,%.0f)   ",
                   static_cast<unsigned long long>(samples), static_cast<double>(last_t - first_t) / 1e9, l.px.x,
                   l.px.y, rr.px.x, rr.px.y);
    }
  }
  if (!o.quiet && !o.json) std::fprintf(stderr, "\n");
  if (Status s = trace->commit(); !s) return cli::report(s.error(), "foveald");

  nlohmann::json states;
  for (Eye e : kEyes)
    for (int k = 0; k < 5; ++k)
      states[eye_name(e)][fovea_state_name(static_cast<FoveaState>(k))] = state_counts[static_cast<int>(e)][k];
  nlohmann::json summary = {
      {"source", {{"driver", "replay"}, {"path", ro.path}, {"nominal_rate_hz", source.info().nominal_rate_hz}}},
      {"display_model", model.name},
      {"speed", o.speed},
      {"samples", samples},
      {"duration_s", static_cast<double>(last_t - first_t) / 1e9},
      {"wall_s", static_cast<double>(monotonic_now_ns() - wall0) / 1e9},
      {"fovea_states", states},
      {"trace", o.out + "/trace.csv"}};
  if (!lateness_ms.empty()) {
    const double worst = lateness_ms[worst_index];
    summary["pacing_error_ms"] = {{"p50", percentile(lateness_ms, 0.5)},
                                  {"p99", percentile(lateness_ms, 0.99)},
                                  {"max", worst},
                                  {"max_at_sample", worst_index}};
  }
  rusage ru{};
  ::getrusage(RUSAGE_SELF, &ru);
  summary["peak_rss_mb"] = static_cast<double>(ru.ru_maxrss) / 1024.0;
  if (Status s = write_file_atomically(o.out + "/summary.json", summary.dump(2) + "\n"); !s)
    return cli::report(s.error(), "foveald");
  if (o.json) cli::print_json(summary);
  else if (!o.quiet)
    std::printf("foveald: replayed %llu samples from %s -> %s/trace.csv, %s/summary.json\n",
                static_cast<unsigned long long>(samples), ro.path.c_str(), o.out.c_str(), o.out.c_str());
  return cli::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"foveald: the foveal runtime daemon (gaze -> fovea -> compositor)"};
  app.set_version_flag("--version", "foveald 0.1.0");
  Options o;
  app.add_option("--replay", o.replay, "Native gaze log to replay (default: the bundled Vive Pro Eye recording)");
  app.add_option("--display", o.display, "Display-model JSON (default: HTC Vive Pro Eye)");
  app.add_option("--out,-o", o.out, "Output directory for trace.csv and summary.json")->capture_default_str();
  app.add_option("--speed", o.speed, "Replay speed: 1 real time, 0 as fast as possible")->capture_default_str();
  app.add_option("--start", o.start_s, "Replay from this time (s from the log's first sample)");
  app.add_option("--end", o.end_s, "Replay until this time (s from the log's first sample)");
  app.add_flag("--loop", o.loop, "Loop the replay window (needs --end)");
  app.add_flag("--headless", o.headless, "Run without a window (the default for now)");
  app.add_flag("--json", o.json, "Print the summary as JSON");
  app.add_flag("-q,--quiet", o.quiet, "No live status line");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : foveal::cli::kExitBadInput;
  }
  return run(o);
}

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>

#include "commands.hpp"
#include "foveal/core/atomic_file.hpp"
#include "foveal/core/gaze_log.hpp"
#include "foveal/drivers/synthetic_source.hpp"
#include "foveal/runtime/cli.hpp"

namespace foveal::cmd {

void add_synth(CLI::App& app, int& exit_code) {
  struct Args {
    SyntheticOptions opts;
    std::string out, truth;
    bool json = false;
  };
  auto args = std::make_shared<Args>();
  args->opts.duration_s = 60;
  CLI::App* sub = app.add_subcommand("synth", "Generate a synthetic gaze log (and its ground truth)");
  sub->add_option("--out,-o", args->out, "Output native gaze log")->required();
  sub->add_option("--truth", args->truth, "Also write the ground truth CSV here");
  sub->add_option("--seed", args->opts.seed, "Random seed (same seed -> same output)")->capture_default_str();
  sub->add_option("--duration", args->opts.duration_s, "Seconds to generate")->capture_default_str();
  sub->add_option("--rate", args->opts.rate_hz, "Sample rate, Hz")->capture_default_str();
  sub->add_option("--noise", args->opts.noise_deg, "RMS measurement noise per eye, degrees")->capture_default_str();
  sub->add_option("--blink-rate", args->opts.blink_rate_hz, "Blinks per second of fixation")->capture_default_str();
  sub->add_option("--pursuit", args->opts.pursuit_probability, "Share of smooth-pursuit events")->capture_default_str();
  sub->add_flag("--json", args->json, "Print the summary as JSON");
  sub->callback([args, &exit_code] {
    if (Status s = args->opts.validate(); !s) {
      exit_code = cli::report(s.error());
      return;
    }
    if (args->opts.duration_s <= 0) {
      exit_code = cli::report(bad_input("synth: --duration must be > 0"));
      return;
    }
    GazeLogHeader header;
    header.rate_hz = args->opts.rate_hz;
    header.meta["source"] = "synthetic:seed=" + std::to_string(args->opts.seed);
    auto writer = GazeLogWriter::create(args->out, header);
    if (!writer) {
      exit_code = cli::report(writer.error());
      return;
    }
    std::optional<AtomicFile> truth;
    if (!args->truth.empty()) {
      auto f = AtomicFile::create(args->truth);
      if (!f) {
        exit_code = cli::report(f.error());
        return;
      }
      truth.emplace(std::move(f.value()));
      truth->write("t_ns,event,event_index,azimuth_deg,elevation_deg,depth_m,left_dir_x,left_dir_y,left_dir_z,"
                   "right_dir_x,right_dir_y,right_dir_z\n");
    }
    SyntheticGenerator gen(args->opts);
    GazeSample s;
    GazeTruth t;
    const auto total = static_cast<std::uint64_t>(std::ceil(args->opts.duration_s * args->opts.rate_hz));
    cli::Progress progress("synth", total, !args->json);
    std::uint64_t counts[4] = {0, 0, 0, 0};
    while (gen.next(s, t)) {
      if (Status st = writer->write(s); !st) {
        exit_code = cli::report(st.error());
        return;
      }
      ++counts[static_cast<int>(t.event)];
      if (truth) {
        char row[320];
        const int n = std::snprintf(row, sizeof row, "%lld,%s,%u,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n",
                                    static_cast<long long>(t.t_ns), gaze_event_name(t.event), t.event_index,
                                    t.azimuth_deg, t.elevation_deg, t.depth_m, t.direction[0].x, t.direction[0].y,
                                    t.direction[0].z, t.direction[1].x, t.direction[1].y, t.direction[1].z);
        truth->write(std::string_view(row, static_cast<std::size_t>(n)));
      }
      if ((gen.index() & 1023) == 0) progress.update(gen.index());
    }
    progress.finish();
    if (Status st = writer->commit(); !st) {
      exit_code = cli::report(st.error());
      return;
    }
    if (truth)
      if (Status st = truth->commit(); !st) {
        exit_code = cli::report(st.error());
        return;
      }
    nlohmann::json j = {{"output", args->out},  {"truth", args->truth},      {"seed", args->opts.seed},
                        {"samples", gen.index()}, {"rate_hz", args->opts.rate_hz},
                        {"events", {{"fixation", counts[0]}, {"saccade", counts[1]}, {"pursuit", counts[2]}, {"blink", counts[3]}}}};
    if (args->json) cli::print_json(j);
    else
      std::printf("wrote %llu samples -> %s%s%s\n", static_cast<unsigned long long>(gen.index()), args->out.c_str(),
                  args->truth.empty() ? "" : ", truth -> ", args->truth.c_str());
  });
}

}  // namespace foveal::cmd

// `foveal log plot`: a native gaze log or a fovea trace over time, drawn by
// tools/charts/log_chart.py (gaze x/y per eye, tracker state, blinks, markers).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "foveal/core/atomic_file.hpp"
#include "foveal/core/data_paths.hpp"
#include "foveal/core/gaze_log.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/tools/run_program.hpp"

namespace foveal::cmd {

namespace {

bool starts_as_gaze_log(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string first(kGazeLogMagic.size(), '\0');
  in.read(first.data(), static_cast<std::streamsize>(first.size()));
  return in && first == kGazeLogMagic;
}

// The script's one-line message without its own name and the newline.
std::string script_message(std::string err) {
  while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
  if (const auto nl = err.rfind('\n'); nl != std::string::npos) err = err.substr(nl + 1);  // the last line says what went wrong
  const std::string prefix = "log_chart.py: ";
  return err.rfind(prefix, 0) == 0 ? err.substr(prefix.size()) : err;
}

}  // namespace

void add_log_plot(CLI::App& log, int& exit_code) {
  struct Args {
    std::string file, out, trace;
    std::optional<double> start_s, end_s;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = log.add_subcommand("plot", "Plot a native gaze log or a fovea trace (foveald's trace.csv, replay --trace) over time: "
                                             "gaze x/y per eye, tracker state, blinks, markers (PNG)");
  sub->add_option("file", a->file, "Native gaze log (foveal import, record, synth) or fovea trace")->required();
  sub->add_option("--out,-o", a->out, "PNG to write (replaced whole or not at all)")->required();
  sub->add_option("--trace", a->trace, "With a gaze log: its fovea trace (foveal replay LOG --trace), the filter output beside the raw gaze");
  sub->add_option("--start", a->start_s, "Window start, seconds from the first sample");
  sub->add_option("--end", a->end_s, "Window end, seconds from the first sample");
  sub->callback([a, &exit_code] {
    auto fail = [&exit_code](const Error& e) { exit_code = cli::report(e); };
    if (a->start_s && a->end_s && *a->end_s <= *a->start_s) return fail(bad_input("--end must be after --start"));
    if (Status s = check_output_is_not_an_input(a->out, {a->file, a->trace}); !s) return fail(s.error());
    // A native log is read by foveal's own reader first: its checks and messages
    // (file:line: column) are the ones every other command gives.
    if (starts_as_gaze_log(a->file))
      if (auto samples = read_gaze_log(a->file); !samples) return fail(samples.error());
    const std::string python = "/usr/bin/python3", script = data_path("tools/charts/log_chart.py");
    std::vector<std::string> argv = {python, script, a->file, a->out};
    if (!a->trace.empty()) argv.insert(argv.end(), {"--trace", a->trace});
    if (a->start_s) argv.insert(argv.end(), {"--start", std::to_string(*a->start_s)});
    if (a->end_s) argv.insert(argv.end(), {"--end", std::to_string(*a->end_s)});
    auto r = cli::run_program(argv, {.out = false, .err = true});  // no shell: names reach it as one argument each
    if (!r) return fail(r.error());
    if (r->exit_code == cli::kExitBadInput) return fail(bad_input(script_message(r->err)));
    if (!r->ok())
      return fail(io_error("log plot: " + python + " " + script + " ended with " + cli::describe_end(*r) + ": " + script_message(r->err) +
                           "; " + a->out + " is unchanged"));
    std::printf("wrote %s\n", a->out.c_str());
  });
}

}  // namespace foveal::cmd

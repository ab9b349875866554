#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <iostream>

#include "commands.hpp"
#include "foveal/core/atomic_file.hpp"
#include "foveal/import/importers.hpp"
#include "foveal/runtime/cli.hpp"

namespace foveal::cmd {

void add_import(CLI::App& app, int& exit_code) {
  struct Args {
    std::string from, in, out;
    bool json = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("import", "Convert a third-party gaze export into a native gaze log");
  sub->add_option("--from", args->from, "Input format")->required()->check(CLI::IsMember({"sranipal", "pupil"}));
  sub->add_option("input", args->in, "Input file (SRanipal CSV or Pupil Labs gaze_positions.csv)")->required();
  sub->add_option("--out,-o", args->out, "Output native gaze log (written atomically)")->required();
  sub->add_flag("--json", args->json, "Print the summary as JSON");
  sub->callback([args, &exit_code] {
    if (Status s = check_output_is_not_an_input(args->out, {args->in}); !s) {
      exit_code = cli::report(s.error());
      return;
    }
    auto r = args->from == "sranipal" ? import_sranipal(args->in, args->out) : import_pupil(args->in, args->out);
    if (!r) {
      exit_code = cli::report(r.error());
      return;
    }
    const ImportSummary& s = *r;
    if (args->json) {
      cli::print_json({{"format", s.format}, {"input", args->in}, {"output", args->out}, {"samples", s.rows},
                       {"rate_hz", s.rate_hz}, {"invalid_left", s.invalid[0]}, {"invalid_right", s.invalid[1]},
                       {"head_pose", s.head_pose}, {"format_version", s.head_pose ? 2 : 1}});
    } else {
      std::cout << "imported " << s.rows << " samples (" << s.format << ", " << s.rate_hz << " Hz) -> " << args->out
                << "\n  invalid: left " << s.invalid[0] << ", right " << s.invalid[1]
                << (s.head_pose ? "\n  head pose: yes (gaze log v2)" : "\n  head pose: none (gaze log v1)") << "\n";
    }
  });
}

}  // namespace foveal::cmd

// foveal record: reads a tracker and writes what it delivers as a native gaze log,
// riding out unplugs (retry with backoff) until the duration is over or Ctrl-C. With
// --control it serves a control socket whose `mark` requests become marker rows of the
// log; at the end it reports the recording's data quality (docs/quality.md). With
// --head, the headset's own pose goes with each sample (log v2, docs/headset.md).
// The options here; the recording is record_gaze (record/recording.hpp).
#include <CLI/CLI.hpp>

#include <memory>

#include "commands.hpp"
#include "foveal/drivers/probe.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/runtime/control_server.hpp"
#include "record/recording.hpp"

namespace foveal::cmd {

void add_record(CLI::App& app, int& exit_code) {
  struct Args : RecordRequest {
    std::string source, device;
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("record", "Record a tracker's gaze into a native gaze log");
  sub->add_option("--source,-s", args->source, "Source spec (default: auto, the first tracker found):\n" + probe::source_spec_help());
  sub->add_option("--device,-d", args->device, "Short form: an id from `foveal devices`, a hidraw path, psvr2, or auto")
      ->excludes("--source");
  sub->add_option("--out,-o", args->out, "Output native gaze log (written atomically)")->required();
  sub->add_option("--head", args->head, "Also record the headset's own pose with each sample (native log v2):\n" + probe::pose_spec_help());
  sub->add_option("--duration", args->duration_s, "Seconds to record (Ctrl-C stops early)")->capture_default_str();
  sub->add_flag("--control", args->control,
                "Serve a control socket while recording (default " + default_record_socket_path() +
                    "): `foveal ctl mark TEXT` puts a marker row into the log");
  sub->add_option("--control-socket", args->control_socket, "Serve the control socket at this path instead");
  sub->add_option("--targets", args->targets,
                  "Targets CSV (start_s,end_s,azimuth_deg,elevation_deg): the end report gives accuracy");
  sub->add_flag("--json", args->json, "Print the summary as JSON");
  sub->callback([args, &exit_code] {
    if (!(args->duration_s > 0)) {
      exit_code = cli::report(bad_input("record: --duration must be > 0"));
      return;
    }
    auto spec = probe::parse_source_spec(args->source.empty() ? probe::device_spec(args->device) : args->source);
    if (!spec) {
      exit_code = cli::report(spec.error());
      return;
    }
    if (Status st = record_gaze(*spec, *args); !st) exit_code = cli::report(st.error());
  });
}

}  // namespace foveal::cmd

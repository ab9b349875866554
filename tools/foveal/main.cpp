// foveal: the command-line tool (import, log, synth, and more as the runtime grows).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <new>
#include <string>

#include "commands.hpp"
#include "foveal/core/atomic_file.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/version.h"

int main(int argc, char** argv) {
  CLI::App app{"foveal: eye-tracked foveated rendering toolkit (gaze logs, rendering, metrics)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "foveal " FOVEAL_VERSION);
  int exit_code = foveal::cli::kExitOk;
  foveal::remove_temporary_files_on_signals();  // a killed write leaves no OUT.tmp.* behind
  foveal::cmd::add_import(app, exit_code);
  foveal::cmd::add_log(app, exit_code);
  foveal::cmd::add_synth(app, exit_code);
  foveal::cmd::add_profile(app, exit_code);
  foveal::cmd::add_service(app, exit_code);
  foveal::cmd::add_ctl(app, exit_code);
  foveal::cmd::add_calibrate(app, exit_code);
  foveal::cmd::add_replay(app, exit_code);
  foveal::cmd::add_predict_eval(app, exit_code);
  foveal::cmd::add_filter_chart(app, exit_code);
  foveal::cmd::add_render(app, exit_code);
  foveal::cmd::add_foveate(app, exit_code);
  foveal::cmd::add_metrics(app, exit_code);
  foveal::cmd::add_bench(app, exit_code);
  foveal::cmd::add_outputs(app, exit_code);
  foveal::cmd::add_devices(app, exit_code);
  foveal::cmd::add_record(app, exit_code);
  foveal::cmd::add_study(app, exit_code);
#ifdef FOVEAL_HAVE_HID
  foveal::cmd::add_hid(app, exit_code);
#endif
#ifdef FOVEAL_HAVE_OPENXR
  foveal::cmd::add_openxr(app, exit_code);
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : foveal::cli::kExitBadInput;
  } catch (const std::bad_alloc&) {
    // Every command runs inside parse(): an allocation that fails anywhere ends here, as an
    // internal error with a message, not an abort. Outputs are atomic: none is left partial.
    std::string name = "foveal";
    for (const CLI::App* sub = &app; !sub->get_subcommands().empty();) {
      sub = sub->get_subcommands().front();
      name += " " + sub->get_name();
    }
    std::fprintf(stderr,
                 "foveal: error: %s: out of memory (an allocation failed), stopped; files are written whole or not at "
                 "all. Free memory, raise the process's limit or give it smaller input\n",
                 name.c_str());
    return foveal::cli::kExitFailure;
  }
  return exit_code;
}

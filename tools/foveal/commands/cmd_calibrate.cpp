// foveal calibrate: finds the dominant eye and the EFR pair and saves them into a profile
// (docs/calibration.md). The options here; the calibration is run_calibration
// (calibrate/calibration_run.hpp).
#include <CLI/CLI.hpp>

#include <memory>

#include "calibrate/calibration_run.hpp"
#include "commands.hpp"
#include "foveal/runtime/cli.hpp"

namespace foveal::cmd {

void add_calibrate(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<CalibrateRequest>();
  CLI::App* sub = app.add_subcommand(
      "calibrate", "Find the dominant eye and the EFR pair (sigma_d, sigma_nd) and save them into a profile");
  sub->add_option("--profile", a->profile, "Profile to update (created if missing; default: the active one)");
  sub->add_option("--answers", a->answers,
                  "Scripted mode: answers (left/right/same/different, one per prompt) from a file, headless; "
                  "without it: the in-headset window (keys L/R, S/D, Esc; gamepad LB/RB, A/B)");
  sub->add_option("--monitor", a->monitor, "In-headset mode: fullscreen on the monitor whose name contains this");
  sub->add_option("--scene", a->scene, "In-headset mode: the scene of the comparisons (default: the bundled Dungeon)");
  sub->add_option("--gaze-log", a->gaze_log,
                  "Native gaze log recorded during the validation trials: accuracy and precision go into the profile");
  sub->add_option("--gaze", a->gaze,
                  "In-headset mode: read this gaze source (e.g. auto, hid, psvr2) during the validation trials "
                  "for their accuracy and precision")
      ->excludes("--gaze-log")
      ->excludes("--answers");
  sub->add_option("--gaze-targets", a->gaze_targets,
                  "Targets CSV for --gaze-log (start_s,end_s,azimuth_deg,elevation_deg; default: all straight ahead)")
      ->needs("--gaze-log");
  sub->add_flag("--dry-run", a->dry_run, "Report the result without saving it");
  sub->add_flag("--json", a->json, "Print the result as JSON");
  sub->callback([a, &exit_code] {
    if (Status st = run_calibration(*a); !st) exit_code = cli::report(st.error());
  });
}

}  // namespace foveal::cmd

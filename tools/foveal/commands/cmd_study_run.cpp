// `foveal study run`: a perception study of foveation with one participant, the RMFR
// paper's 2AFC or the EFR paper's random test, in the headset window or scripted from
// an answers file (headless), into a trials CSV and a summary (docs/study.md). The options
// here; the study's run is run_study (tools/study/render, foveal::study_render).
#include <CLI/CLI.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/study/study_frames.hpp"
#include "foveal/study/study_run.hpp"
#include "render/render_args.hpp"

namespace foveal::cmd {

namespace {

// The study's options (study_options) and how it is run (StudyRunSettings).
struct Args : StudyRunSettings {
  std::string design = "2afc", participant = "p01";
  std::vector<std::string> scenes, conditions;
  std::string validation_condition = "rmfr:6";
  int repeats = 3, validation_min_score = 4, max_validation_errors = 2;
  double validation_share = 0.3, present_s = 2.0, blank_s = 0.75;
  std::uint64_t seed = 0;
};

Result<StudyOptions> study_options(const Args& a) {
  StudyOptions o;
  if (a.design != "2afc" && a.design != "score") return bad_input("--design: '" + a.design + "' is not 2afc or score");
  o.design = a.design == "2afc" ? StudyDesign::two_afc : StudyDesign::score;
  o.participant = a.participant;
  o.scenes = a.scenes.empty() ? std::vector<std::string>{default_scene()} : a.scenes;
  for (const std::string& s : o.scenes)
    if (s.find_first_of(",\"\n\r") != std::string::npos)
      return bad_input("--scene: '" + s + "': a path with commas, quotes or line ends cannot go into the trials CSV");
  for (const std::string& spec : a.conditions) {
    auto c = parse_study_condition(spec, "--condition");
    if (!c) return c.error();
    if (o.design == StudyDesign::two_afc && !c->uniform())
      return bad_input("--condition: '" + spec + "': a 2AFC condition has one level for both eyes");
    o.conditions.push_back(*c);
  }
  auto v = parse_study_condition(a.validation_condition, "--validation-condition");
  if (!v) return v.error();
  o.validation_condition = *v;
  o.repeats = a.repeats;
  o.validation_share = a.validation_share;
  o.validation_min_score = a.validation_min_score;
  o.max_validation_errors = a.max_validation_errors;
  o.present_s = a.present_s;
  o.blank_s = a.blank_s;
  o.seed = a.seed;
  if (Status s = o.validate(); !s) return s.error();
  if (Status s = check_study_methods(o); !s) return s.error();
  return o;
}

}  // namespace

void add_study_run(CLI::App& study, int& exit_code) {
  auto a = std::make_shared<Args>();
  CLI::App* sub = study.add_subcommand(
      "run", "Run a study with one participant: 2AFC between conditions, or the random test's scores");
  sub->add_option("--design", a->design, "2afc (the RMFR paper's) or score (the EFR paper's random test)")
      ->check(CLI::IsMember({"2afc", "score"}))
      ->capture_default_str();
  sub->add_option("--participant", a->participant, "Participant id (a CSV field)")->capture_default_str();
  sub->add_option("--condition", a->conditions,
                  "METHOD[:SIGMA[/SIGMA_ND]][:F], repeatable: 2AFC compares every pair, score rates each against full")
      ->required();
  sub->add_option("--scene", a->scenes, "Scene(s), repeatable (default: the bundled Dungeon)");
  sub->add_option("--repeats", a->repeats, "Trials per pair (2AFC) or condition (score), per scene")->capture_default_str();
  sub->add_option("--validation-share", a->validation_share, "Share of validation trials among all")->capture_default_str();
  sub->add_option("--validation-condition", a->validation_condition,
                  "2AFC validation: shown against full, which must be chosen")->capture_default_str();
  sub->add_option("--validation-min-score", a->validation_min_score,
                  "Score validation (identical frames): a lower score fails")->capture_default_str();
  sub->add_option("--max-validation-errors", a->max_validation_errors,
                  "More failed validation trials discard the participant's data")->capture_default_str();
  sub->add_option("--present-s", a->present_s, "Seconds per presentation")->capture_default_str();
  sub->add_option("--blank-s", a->blank_s, "Seconds of black between the presentations")->capture_default_str();
  sub->add_option("--seed", a->seed, "Trial order seed (0: from the participant id)")->capture_default_str();
  sub->add_option("--dominant", a->dominant, "The participant's dominant eye (sigma_d goes there)")
      ->check(CLI::IsMember({"left", "right"}))
      ->capture_default_str();
  sub->add_option("--size", a->size, "Output size WxH (default: the display model's)");
  sub->add_option("--answers", a->answers,
                  "Scripted mode, headless: one response per trial (1/2 for 2AFC, 1-5 for scores; KEY@SECONDS "
                  "gives the response time); without it: the headset window");
  sub->add_option("--frames-out", a->frames_out, "Scripted mode: save each presentation as DIR/trial_NNN_P.png")
      ->needs("--answers");
  sub->add_option("--monitor", a->monitor, "Headset mode: fullscreen on the monitor whose name contains this");
  sub->add_option("--out,-o", a->out, "Directory for trials.csv and summary.json")->required();
  sub->add_flag("--json", a->json, "Print the summary as JSON");
  sub->add_flag("--no-jod", a->no_jod,
                "Leave out each condition's predicted JOD against full (conditions.csv): a render and a still's JOD per "
                "condition and scene, seconds each at the headset's size on a CPU renderer");
  sub->callback([a, &exit_code] {
    auto options = study_options(*a);
    if (!options) {
      exit_code = cli::report(options.error());
      return;
    }
    if (Status st = run_study(*options, *a); !st) exit_code = cli::report(st.error());
  });
}

}  // namespace foveal::cmd

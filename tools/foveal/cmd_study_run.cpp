// `foveal study run`: a perception study of foveation with one participant, the RMFR
// paper's 2AFC or the EFR paper's random test, in the headset window or scripted from
// an answers file (headless), into a trials CSV and a summary (docs/study.md).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "commands.hpp"
#include "foveal/core/atomic_file.hpp"
#include "foveal/core/json_file.hpp"
#include "foveal/core/json_text.hpp"
#include "foveal/core/read_file.hpp"
#include "foveal/image/image.hpp"
#include "foveal/render/egl_context.hpp"
#include "foveal/runtime/args.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/study/study_session.hpp"
#include "foveal/study/study_stats.hpp"
#include "render_args.hpp"
#include "scripted_words.hpp"
#include "study_jod.hpp"
#include "study_window.hpp"

namespace foveal::cmd {

namespace {

struct Args {
  std::string design = "2afc", participant = "p01", answers, out, frames_out, monitor, size, dominant = "right";
  std::vector<std::string> scenes, conditions;
  std::string validation_condition = "rmfr:6";
  int repeats = 3, validation_min_score = 4, max_validation_errors = 2;
  double validation_share = 0.3, present_s = 2.0, blank_s = 0.75;
  std::uint64_t seed = 0;
  bool json = false, no_jod = false;
};

using ScriptedResponse = ScriptedWord<StudyResponse>;

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

// Scripted: each trial's two presentations are rendered (and saved when asked), then
// the next response is taken; pauses are counted, not waited for.
Status run_scripted(StudySession& session, StudyFrames& frames, const Args& a) {
  auto responses = read_scripted_words<StudyResponse>(a.answers, parse_study_response);
  if (!responses) return responses.error();
  for (const ScriptedResponse& r : *responses) {
    if (session.done())
      return bad_input(a.answers + ":" + std::to_string(r.line) + ": more responses than trials" +
                       (session.discarded() ? " (the participant was discarded before this one)" : ""));
    session.resume();
    const PlannedTrial& t = session.trial();
    for (int p = 0; p < 2; ++p) {
      if (Status st = frames.draw(t, p); !st) return st;
      if (!a.frames_out.empty()) {
        char name[64];
        std::snprintf(name, sizeof name, "/trial_%03d_%d.png", t.index, p + 1);
        if (Status st = image::save_png(a.frames_out + name, frames.compositor().read_image()); !st) return st;
      }
    }
    if (Status st = session.respond(r.value); !st)
      return bad_input(a.answers + ":" + std::to_string(r.line) + ": trial " + std::to_string(t.index) + ": " +
                       st.error().message);
  }
  if (!session.done())
    return bad_input(a.answers + ": responses ended at trial " + std::to_string(session.trial().index) + " of " +
                     std::to_string(session.planned()));
  return {};
}

nlohmann::json summary_json(const StudySession& s, const Args& a, const std::optional<StudyStats>& stats,
                            const std::optional<StudyJod>& jod) {
  const StudyOptions& o = s.options();
  nlohmann::json conditions = nlohmann::json::array();
  for (const StudyCondition& c : o.conditions) conditions.push_back(c.label());
  int tests = 0;
  for (const TrialResult& r : s.results()) tests += r.trial.validation ? 0 : 1;
  nlohmann::json j = {
      {"participant", o.participant},
      {"design", study_design_name(o.design)},
      {"mode", a.answers.empty() ? "headset" : "scripted"},
      {"seed", study_seed(o)},
      {"scenes", o.scenes},
      {"conditions", conditions},
      {"dominant_eye", a.dominant},
      {"repeats", o.repeats},
      {"timing_s", {{"presentation", o.present_s}, {"black", o.blank_s}}},
      {"trials", {{"planned", s.planned()}, {"answered", s.results().size()}, {"test", tests}}},
      {"validation",
       {{"trials", s.validation_trials()},
        {"failures", s.validation_failures()},
        {"max_errors", o.max_validation_errors},
        {"share", o.validation_share},
        {"check", o.design == StudyDesign::two_afc ? "full chosen over " + o.validation_condition.label()
                                                   : "identical frames scored >= " + std::to_string(o.validation_min_score)}}},
      {"pauses", s.pauses()},
      {"discarded", s.discarded()}};
  if (stats) {
    nlohmann::json pairs = nlohmann::json::array(), scores = nlohmann::json::array();
    for (const PairVotes& p : stats->pairs) {
      pairs.push_back({{"first", p.first}, {"second", p.second}, {"trials", p.trials}, {"votes_first", p.votes_first},
                       {"votes_second", p.votes_second}, {"p_value", p.p_value}});
      if (jod) pairs.back().update({{"predicted_jod_first", predicted_jod_of(*jod, p.first)},
                                    {"predicted_jod_second", predicted_jod_of(*jod, p.second)}});
    }
    for (const ConditionScore& c : stats->scores) {
      scores.push_back({{"condition", c.condition}, {"trials", c.trials}, {"mean", c.mean}});
      if (jod) scores.back()["predicted_jod"] = predicted_jod_of(*jod, c.condition);
    }
    j["pairs"] = pairs;
    j["scores"] = scores;
    j["trials_csv"] = a.out + "/trials.csv";
  }
  if (jod) {
    nlohmann::json rows = nlohmann::json::array();
    for (const ConditionJod& r : jod->rows)
      rows.push_back({{"scene", r.scene}, {"condition", r.condition.label()}, {"jod", r.jod.combined}, {"left", r.jod.left},
                      {"right", r.jod.right}});
    j["predicted_jod"] = jod->settings;
    j["predicted_jod"]["conditions"] = rows;
    j["conditions_csv"] = a.out + "/conditions.csv";
  }
  return j;
}

int run(const Args& a) {
  auto options = study_options(a);
  if (!options) return cli::report(options.error());
  auto plan = plan_study(*options);
  if (!plan) return cli::report(plan.error());
  const Eye dominant = a.dominant == "left" ? Eye::left : Eye::right;
  // The headset's own size (the display model's) unless asked otherwise.
  const DisplayModel model = DisplayModel::vive_pro_eye();
  std::pair<int, int> size{model.output_width(), model.output_height()};
  if (!a.size.empty()) {
    auto s = cli::parse_size(a.size, "--size");
    if (!s) return cli::report(s.error());
    if (s->first % 2) return cli::report(bad_input("--size: the width must be even (two eyes side by side)"));
    size = *s;
  }
  std::error_code ec;
  for (const std::string& dir : {a.out, a.frames_out}) {
    if (dir.empty()) continue;
    std::filesystem::create_directories(dir, ec);
    if (ec) return cli::report(io_error(dir + ": cannot create directory: " + ec.message()));
  }

  StudySession session(*options, std::move(*plan));
  // After the participant's last answer (so nobody waits for it): each condition's
  // predicted JOD against full, on the frames the study showed.
  std::optional<StudyJod> jod;
  auto predict = [&](StudyFrames& frames) -> Status {
    if (a.no_jod || session.discarded()) return {};
    if (!a.json) std::fprintf(stderr, "study: predicting JOD of %zu conditions\n", options->conditions.size() * options->scenes.size());
    auto j = predict_study_jod(frames, *options, model);
    if (!j) return j.error();
    jod = std::move(*j);
    return {};
  };
  if (a.answers.empty()) {
    render::WindowOptions wo;
    wo.monitor = a.monitor;
    wo.title = a.design == "2afc" ? "foveal study: 1/left first, 2/right second; Esc quits"
                                  : "foveal study: 1 (very different) .. 5 (no difference); Esc quits";
    auto window = render::Window::open(wo);
    if (!window) {
      Error e = window.error();
      if (e.kind == ErrorKind::unsupported) e.message += " (no display? the scripted mode works headless: --answers FILE)";
      return cli::report(e);
    }
    auto frames = StudyFrames::create(*options, dominant, size.first, size.second);
    if (!frames) return cli::report(frames.error());
    if (Status st = run_study_window(session, *frames, *window); !st) return cli::report(st.error());
    if (Status st = predict(*frames); !st) return cli::report(st.error());
  } else {
    auto ctx = gl::EglContext::create();
    if (!ctx) return cli::report(ctx.error());
    auto frames = StudyFrames::create(*options, dominant, size.first, size.second);
    if (!frames) return cli::report(frames.error());
    if (Status st = run_scripted(session, *frames, a); !st) return cli::report(st.error());
    if (Status st = predict(*frames); !st) return cli::report(st.error());
  }

  // A discarded participant leaves only the summary saying so: their trials are not data.
  const std::string trials_path = a.out + "/trials.csv";
  std::optional<StudyStats> stats;
  if (!session.discarded()) {
    if (Status st = write_file_atomically(trials_path, study_trials_csv(session)); !st) return cli::report(st.error());
    auto trials = read_study_trials(trials_path);
    if (!trials) return cli::report(trials.error());
    stats = compute_study_stats(*trials);
  }
  const std::string conditions_path = a.out + "/conditions.csv";
  if (jod)
    if (Status st = write_file_atomically(conditions_path, study_conditions_csv(*jod)); !st) {
      std::filesystem::remove(trials_path, ec);
      return cli::report(st.error());
    }
  const nlohmann::json summary = summary_json(session, a, stats, jod);
  if (Status st = write_file_atomically(a.out + "/summary.json", json_text(summary, 2) + "\n"); !st) {
    std::filesystem::remove(trials_path, ec);
    std::filesystem::remove(conditions_path, ec);
    return cli::report(st.error());
  }
  if (a.json) cli::print_json(summary);
  else
    std::printf("study %s, participant %s: %zu of %zu trials, validation %d/%d passed, %d pauses -> %s\n",
                study_design_name(options->design), options->participant.c_str(), session.results().size(),
                session.planned(), session.validation_trials() - session.validation_failures(),
                session.validation_trials(), session.pauses(),
                session.discarded() ? (a.out + "/summary.json (participant discarded)").c_str() : trials_path.c_str());
  if (jod && !a.json) {
    for (const ConditionJod& r : jod->rows)
      std::printf("  predicted JOD %.2f (left %.2f, right %.2f)  %s%s%s\n", r.jod.combined, r.jod.left, r.jod.right,
                  r.condition.label().c_str(), options->scenes.size() > 1 ? " on " : "",
                  options->scenes.size() > 1 ? r.scene.c_str() : "");
    std::printf("  -> %s\n", conditions_path.c_str());
  }
  if (session.discarded())
    return cli::report(bad_input("participant " + options->participant + "'s data discarded: " +
                                 std::to_string(session.validation_failures()) + " failed validation trials (at most " +
                                 std::to_string(options->max_validation_errors) + " allowed); no trials were written"));
  return cli::kExitOk;
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
  sub->callback([a, &exit_code] { exit_code = run(*a); });
}

}  // namespace foveal::cmd

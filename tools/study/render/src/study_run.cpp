#include "foveal/study/study_run.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <optional>

#include "foveal/core/atomic_file.hpp"
#include "foveal/core/json_text.hpp"
#include "foveal/image/image.hpp"
#include "foveal/render/egl_context.hpp"
#include "foveal/runtime/args.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/study/study_jod.hpp"
#include "foveal/study/study_session.hpp"
#include "foveal/study/study_stats.hpp"
#include "foveal/study/study_window.hpp"
#include "foveal/tools/scripted_words.hpp"

namespace foveal {

namespace {

using ScriptedResponse = cli::ScriptedWord<StudyResponse>;

// Scripted: each trial's two presentations are rendered (and saved when asked), then
// the next response is taken; pauses are counted, not waited for.
Status run_scripted(StudySession& session, StudyFrames& frames, const StudyRunSettings& a) {
  auto responses = cli::read_scripted_words<StudyResponse>(a.answers, parse_study_response);
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

nlohmann::json summary_json(const StudySession& s, const StudyRunSettings& a, const std::optional<StudyStats>& stats,
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

}  // namespace

Status run_study(const StudyOptions& options, const StudyRunSettings& a) {
  auto plan = plan_study(options);
  if (!plan) return plan.error();
  const Eye dominant = a.dominant == "left" ? Eye::left : Eye::right;
  // The headset's own size (the display model's) unless asked otherwise.
  const DisplayModel model = DisplayModel::vive_pro_eye();
  std::pair<int, int> size{model.output_width(), model.output_height()};
  if (!a.size.empty()) {
    auto s = cli::parse_size(a.size, "--size");
    if (!s) return s.error();
    if (s->first % 2) return bad_input("--size: the width must be even (two eyes side by side)");
    size = *s;
  }
  std::error_code ec;
  for (const std::string& dir : {a.out, a.frames_out}) {
    if (dir.empty()) continue;
    std::filesystem::create_directories(dir, ec);
    if (ec) return io_error(dir + ": cannot create directory: " + ec.message());
  }

  StudySession session(options, std::move(*plan));
  // After the participant's last answer (so nobody waits for it): each condition's
  // predicted JOD against full, on the frames the study showed.
  std::optional<StudyJod> jod;
  auto predict = [&](StudyFrames& frames) -> Status {
    if (a.no_jod || session.discarded()) return {};
    if (!a.json) std::fprintf(stderr, "study: predicting JOD of %zu conditions\n", options.conditions.size() * options.scenes.size());
    auto j = predict_study_jod(frames, options, model);
    if (!j) return j.error();
    jod = std::move(*j);
    return {};
  };
  if (a.answers.empty()) {
    render::WindowOptions wo;
    wo.monitor = a.monitor;
    wo.title = options.design == StudyDesign::two_afc ? "foveal study: 1/left first, 2/right second; Esc quits"
                                  : "foveal study: 1 (very different) .. 5 (no difference); Esc quits";
    auto window = render::Window::open(wo);
    if (!window) {
      Error e = window.error();
      if (e.kind == ErrorKind::unsupported) e.message += " (no display? the scripted mode works headless: --answers FILE)";
      return e;
    }
    auto frames = StudyFrames::create(options, dominant, size.first, size.second);
    if (!frames) return frames.error();
    if (Status st = run_study_window(session, *frames, *window); !st) return st.error();
    if (Status st = predict(*frames); !st) return st.error();
  } else {
    auto ctx = gl::EglContext::create();
    if (!ctx) return ctx.error();
    auto frames = StudyFrames::create(options, dominant, size.first, size.second);
    if (!frames) return frames.error();
    if (Status st = run_scripted(session, *frames, a); !st) return st.error();
    if (Status st = predict(*frames); !st) return st.error();
  }

  // A discarded participant leaves only the summary saying so: their trials are not data.
  const std::string trials_path = a.out + "/trials.csv";
  std::optional<StudyStats> stats;
  if (!session.discarded()) {
    if (Status st = write_file_atomically(trials_path, study_trials_csv(session)); !st) return st.error();
    auto trials = read_study_trials(trials_path);
    if (!trials) return trials.error();
    stats = compute_study_stats(*trials);
  }
  const std::string conditions_path = a.out + "/conditions.csv";
  if (jod)
    if (Status st = write_file_atomically(conditions_path, study_conditions_csv(*jod)); !st) {
      std::filesystem::remove(trials_path, ec);
      return st.error();
    }
  const nlohmann::json summary = summary_json(session, a, stats, jod);
  if (Status st = write_file_atomically(a.out + "/summary.json", json_text(summary, 2) + "\n"); !st) {
    std::filesystem::remove(trials_path, ec);
    std::filesystem::remove(conditions_path, ec);
    return st.error();
  }
  if (a.json) cli::print_json(summary);
  else
    std::printf("study %s, participant %s: %zu of %zu trials, validation %d/%d passed, %d pauses -> %s\n",
                study_design_name(options.design), options.participant.c_str(), session.results().size(),
                session.planned(), session.validation_trials() - session.validation_failures(),
                session.validation_trials(), session.pauses(),
                session.discarded() ? (a.out + "/summary.json (participant discarded)").c_str() : trials_path.c_str());
  if (jod && !a.json) {
    for (const ConditionJod& r : jod->rows)
      std::printf("  predicted JOD %.2f (left %.2f, right %.2f)  %s%s%s\n", r.jod.combined, r.jod.left, r.jod.right,
                  r.condition.label().c_str(), options.scenes.size() > 1 ? " on " : "",
                  options.scenes.size() > 1 ? r.scene.c_str() : "");
    std::printf("  -> %s\n", conditions_path.c_str());
  }
  if (session.discarded())
    return bad_input("participant " + options.participant + "'s data discarded: " +
                                 std::to_string(session.validation_failures()) + " failed validation trials (at most " +
                                 std::to_string(options.max_validation_errors) + " allowed); no trials were written");
  return {};
}

}  // namespace foveal

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <sstream>

#include "calibration_window.hpp"
#include "commands.hpp"
#include "foveal/core/json_file.hpp"
#include "foveal/core/read_file.hpp"
#include "foveal/runtime/calibration.hpp"
#include "foveal/runtime/profile.hpp"
#include "foveal/tools/cli.hpp"

namespace foveal::cmd {

namespace {

struct ScriptedAnswer {
  Answer answer;
  int line;
};

// One answer per word; '#' starts a comment.
Result<std::vector<ScriptedAnswer>> read_answers(const std::string& path) {
  auto text = read_regular_file(path, kMaxJsonFileBytes, "answers file");
  if (!text) return text.error();
  std::istringstream in(*text);
  std::vector<ScriptedAnswer> out;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    std::string w;
    while (words >> w) {
      auto a = parse_answer(w);
      if (!a) return bad_input(path + ":" + std::to_string(n) + ": " + a.error().message);
      out.push_back({*a, n});
    }
  }
  return out;
}

}  // namespace

void add_calibrate(CLI::App& app, int& exit_code) {
  struct Args {
    std::string profile, answers, monitor, scene;
    bool json = false, dry_run = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "calibrate", "Find the dominant eye and the EFR pair (sigma_d, sigma_nd) and save them into a profile");
  sub->add_option("--profile", a->profile, "Profile to update (created if missing; default: the active one)");
  sub->add_option("--answers", a->answers,
                  "Scripted mode: answers (left/right/same/different, one per prompt) from a file, headless; "
                  "without it: the in-headset window (keys L/R, S/D, Esc; gamepad LB/RB, A/B)");
  sub->add_option("--monitor", a->monitor, "In-headset mode: fullscreen on the monitor whose name contains this");
  sub->add_option("--scene", a->scene, "In-headset mode: the scene of the comparisons (default: the bundled Dungeon)");
  sub->add_flag("--dry-run", a->dry_run, "Report the result without saving it");
  sub->add_flag("--json", a->json, "Print the result as JSON");
  sub->callback([a, &exit_code] {
    auto fail = [&exit_code](const Error& e) { exit_code = cli::report(e); };
    Calibration cal;
    std::vector<nlohmann::json> steps;
    if (a->answers.empty()) {
      // In-headset mode: the same state machine, answered from the keyboard or a gamepad.
      CalibrationWindowOptions wo;
      wo.monitor = a->monitor;
      wo.scene = a->scene;
      if (Status st = run_calibration_window(cal, wo); !st) {
        Error e = st.error();
        if (e.kind == ErrorKind::unsupported) e.message += " (no display? the scripted mode works headless: --answers FILE)";
        return fail(e);
      }
    }
    std::vector<ScriptedAnswer> scripted;
    if (!a->answers.empty()) {
      auto answers = read_answers(a->answers);
      if (!answers) return fail(answers.error());
      scripted = std::move(*answers);
    }
    for (const ScriptedAnswer& s : scripted) {
      if (cal.done()) return fail(bad_input(a->answers + ":" + std::to_string(s.line) + ": more answers than prompts"));
      const CalibrationPrompt p = cal.prompt();
      if (Status st = cal.answer(s.answer); !st)
        return fail(bad_input(a->answers + ":" + std::to_string(s.line) + ": " + calibration_stage_name(p.stage) +
                              " trial " + std::to_string(p.trial + 1) + ": " + st.error().message));
      steps.push_back({{"stage", calibration_stage_name(p.stage)}, {"trial", p.trial}, {"sigma_left", p.sigma_left},
                       {"sigma_right", p.sigma_right}, {"answer", answer_name(s.answer)}});
    }
    if (!cal.done())  // only the scripted mode can end early
      return fail(bad_input(a->answers + ": answers ended during " + calibration_stage_name(cal.prompt().stage) +
                            " (trial " + std::to_string(cal.prompt().trial + 1) + ")"));
    const CalibrationResult& r = cal.result();
    const ProfileStore store = ProfileStore::user();
    auto lock = store.lock();  // the profile is read, changed and saved
    if (!lock) return fail(lock.error());
    const std::string name = a->profile.empty() ? store.active() : a->profile;
    Profile p;
    p.name = name;
    if (store.exists(name)) {
      auto loaded = store.load(name);
      if (!loaded) return fail(loaded.error());
      p = *loaded;
    }
    p.dominant_eye = r.dominant_eye;
    p.sigma_d = r.sigma_uniform;
    p.sigma_nd = r.sigma_non_dominant;
    const bool save = r.passed() && !a->dry_run;
    nlohmann::json j = {{"profile", name},
                        {"dominant_eye", eye_name(r.dominant_eye)},
                        {"dominant_consistent", r.dominant_consistent},
                        {"sigma_d", r.sigma_uniform},
                        {"sigma_nd", r.sigma_non_dominant},
                        {"validation", {{"trials", r.validation_trials}, {"failures", r.validation_failures}, {"passed", r.passed()}}},
                        {"saved", save},
                        {"steps", steps}};
    if (save)
      if (Status st = store.save(p); !st) return fail(st.error());
    if (a->json) cli::print_json(j);
    else
      std::printf("dominant eye %s%s, sigma_d %.1f, sigma_nd %.1f; validation %d/%d identical pairs right -> %s\n",
                  eye_name(r.dominant_eye), r.dominant_consistent ? "" : " (trials disagreed)", r.sigma_uniform,
                  r.sigma_non_dominant, r.validation_trials - r.validation_failures, r.validation_trials,
                  save ? ("saved to profile " + name).c_str() : a->dry_run ? "not saved (dry run)" : "NOT saved");
    if (!r.passed())
      return fail(bad_input("calibration rejected: " + std::to_string(r.validation_failures) + " of " +
                            std::to_string(r.validation_trials) +
                            " identical pairs were answered 'different'; nothing was saved, please run it again"));
  });
}

}  // namespace foveal::cmd

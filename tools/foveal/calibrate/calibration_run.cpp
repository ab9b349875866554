#include "calibrate/calibration_run.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <optional>
#include <span>
#include <vector>

#include "calibrate/calibration_window.hpp"
#include "foveal/core/gaze_log.hpp"
#include "foveal/drivers/probe.hpp"
#include "foveal/quality/gaze_quality.hpp"
#include "foveal/quality/quality_targets.hpp"
#include "foveal/runtime/calibration.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/runtime/profile.hpp"
#include "foveal/tools/scripted_words.hpp"

namespace foveal::cmd {

namespace {

using ScriptedAnswer = cli::ScriptedWord<Answer>;

double mean_finite(const std::vector<double>& v) {
  double sum = 0;
  int n = 0;
  for (double x : v)
    if (std::isfinite(x)) sum += x, ++n;
  return n ? sum / n : ProfileGazeQuality::kNaN;
}

// The validation trials' gaze (docs/calibration.md, "Gaze accuracy and precision"):
// precision is the mean over the fixation targets of their RMS-S2S and STD, accuracy the
// mean of their offsets; data loss is over all the samples.
Result<ProfileGazeQuality> validation_gaze_quality(std::span<const GazeSample> samples, double rate_hz,
                                                   std::vector<QualityTarget> targets, const std::string& source) {
  if (samples.size() < 2) return bad_input(source + ": too few gaze samples to measure the validation trials");
  QualityOptions qo;
  qo.targets = std::move(targets);
  auto q = compute_gaze_quality(samples, rate_hz, qo);
  if (!q) return Error{q.error().kind, source + ": " + q.error().message};
  ProfileGazeQuality out;
  out.source = source;
  out.targets = static_cast<int>(q->targets.size());
  for (std::size_t c = 0; c < out.channels.size(); ++c) {
    std::vector<double> rms, sd;
    for (const TargetQuality& t : q->targets) {
      rms.push_back(t.channels[c].rms_s2s_deg);
      sd.push_back(t.channels[c].std_deg);
    }
    out.channels[c] = {q->accuracy[c].offset_deg, mean_finite(rms), mean_finite(sd), q->channels[c].data_loss_pct};
  }
  return out;
}

// A log recorded while the fixation targets were shown, and the targets' times and
// places; without a targets file the whole log is one fixation straight ahead, the
// validation stimulus's central target.
Result<ProfileGazeQuality> logged_gaze_quality(const std::string& log, const std::string& targets_file) {
  GazeLogHeader header;
  auto samples = read_gaze_log(log, &header);
  if (!samples) return samples.error();
  std::vector<QualityTarget> targets;
  if (!targets_file.empty()) {
    auto t = read_quality_targets(targets_file);
    if (!t) return t.error();
    targets = std::move(*t);
  } else if (!samples->empty()) {
    const double duration_s = static_cast<double>(samples->back().t_ns - samples->front().t_ns) / 1e9;
    targets = {QualityTarget{0.0, duration_s, FickAngles{0, 0}, log + " (straight ahead)"}};
  }
  return validation_gaze_quality(*samples, header.rate_hz, std::move(targets), log);
}

// The headset's validation trials read live: each trial's fixation window is a target
// straight ahead.
Result<ProfileGazeQuality> live_gaze_quality(const ValidationGaze& g, double rate_hz, const std::string& spec) {
  if (g.samples.size() < 2) return validation_gaze_quality(g.samples, rate_hz, {}, spec);
  const TimeNs t0 = g.samples.front().t_ns, t1 = g.samples.back().t_ns;
  std::vector<QualityTarget> targets;
  for (const auto& [from, to] : g.fixations) {
    const TimeNs a = std::max(from, t0), b = std::min(to, t1);
    if (b > a)
      targets.push_back({static_cast<double>(a - t0) / 1e9, static_cast<double>(b - t0) / 1e9, FickAngles{0, 0},
                         spec + " validation trial " + std::to_string(targets.size() + 1)});
  }
  if (targets.empty()) return bad_input(spec + ": no gaze samples during the validation trials' fixation targets");
  return validation_gaze_quality(g.samples, rate_hz, std::move(targets), spec);
}

nlohmann::json gaze_quality_json(const ProfileGazeQuality& g) {
  // As the profile stores it (NaN: null).
  Profile p;
  p.gaze_quality = g;
  return p.to_json()["gaze_quality"];
}

}  // namespace

Status run_calibration(const CalibrateRequest& a) {
  // The gaze figures first: a bad log stops the command before anyone is asked anything.
  std::optional<ProfileGazeQuality> gaze;
  if (!a.gaze_log.empty()) {
    auto g = logged_gaze_quality(a.gaze_log, a.gaze_targets);
    if (!g) return g.error();
    gaze = *g;
  }
  Calibration cal;
  std::vector<nlohmann::json> steps;
  std::optional<CalibrationDisplay> judged_on;  // the in-headset mode's picture
  if (a.answers.empty()) {
    // In-headset mode: the same state machine, answered from the keyboard or a gamepad.
    CalibrationWindowOptions wo;
    wo.monitor = a.monitor;
    wo.scene = a.scene;
    std::optional<probe::OpenedSource> source;
    ValidationGaze live;
    if (!a.gaze.empty()) {
      auto spec = probe::parse_source_spec(a.gaze);
      if (!spec) return spec.error();
      auto opened = probe::make_source(*spec);
      if (!opened) return opened.error();
      source.emplace(std::move(*opened));
      if (Status st = source->source->open(); !st) return st.error();
      if (Status st = source->source->start(); !st) return st.error();
      wo.gaze = source->source.get();
    }
    Status st = run_calibration_window(cal, wo, source ? &live : nullptr, &judged_on.emplace());
    if (source) source->source->close();
    if (!st) {
      Error e = st.error();
      if (e.kind == ErrorKind::unsupported) e.message += " (no display? the scripted mode works headless: --answers FILE)";
      return e;
    }
    if (source) {
      const double rate = source->source->info().nominal_rate_hz > 0 ? source->source->info().nominal_rate_hz : 120;
      auto g = live_gaze_quality(live, rate, a.gaze);
      if (!g) return g.error();
      gaze = *g;
    }
  }
  std::vector<ScriptedAnswer> scripted;
  if (!a.answers.empty()) {
    auto answers = cli::read_scripted_words<Answer>(a.answers, parse_answer);
    if (!answers) return answers.error();
    scripted = std::move(*answers);
  }
  for (const ScriptedAnswer& s : scripted) {
    if (cal.done()) return bad_input(a.answers + ":" + std::to_string(s.line) + ": more answers than prompts");
    const CalibrationPrompt p = cal.prompt();
    if (Status st = cal.answer(s.value); !st)
      return bad_input(a.answers + ":" + std::to_string(s.line) + ": " + calibration_stage_name(p.stage) +
                       " trial " + std::to_string(p.trial + 1) + ": " + st.error().message);
    steps.push_back({{"stage", calibration_stage_name(p.stage)}, {"trial", p.trial}, {"sigma_left", p.sigma_left},
                     {"sigma_right", p.sigma_right}, {"answer", answer_name(s.value)}});
  }
  if (!cal.done())  // only the scripted mode can end early
    return bad_input(a.answers + ": answers ended during " + calibration_stage_name(cal.prompt().stage) +
                     " (trial " + std::to_string(cal.prompt().trial + 1) + ")");
  const CalibrationResult& r = cal.result();
  const ProfileStore store = ProfileStore::user();
  auto lock = store.lock();  // the profile is read, changed and saved
  if (!lock) return lock.error();
  auto active = store.active();
  if (!active) return active.error();
  const std::string name = a.profile.empty() ? *active : a.profile;
  Profile p;
  p.name = name;
  if (store.exists(name)) {
    auto loaded = store.load(name);
    if (!loaded) return loaded.error();
    p = *loaded;
  }
  p.dominant_eye = r.dominant_eye;
  p.sigma_d = r.sigma_uniform;
  p.sigma_nd = r.sigma_non_dominant;
  if (gaze) p.gaze_quality = gaze;
  const bool save = r.passed() && !a.dry_run;
  nlohmann::json j = {{"profile", name},
                      {"dominant_eye", eye_name(r.dominant_eye)},
                      {"dominant_consistent", r.dominant_consistent},
                      {"sigma_d", r.sigma_uniform},
                      {"sigma_nd", r.sigma_non_dominant},
                      {"validation", {{"trials", r.validation_trials}, {"failures", r.validation_failures}, {"passed", r.passed()}}},
                      {"gaze_quality", gaze ? gaze_quality_json(*gaze) : nlohmann::json(nullptr)},
                      {"saved", save},
                      {"judged_on", judged_on ? nlohmann::json{{"frames", {judged_on->frame_width, judged_on->frame_height}},
                                                               {"shown", {judged_on->shown_width, judged_on->shown_height}},
                                                               {"scale", judged_on->scale()},
                                                               {"monitor", judged_on->monitor.empty() ? nlohmann::json(nullptr)
                                                                                                      : nlohmann::json(judged_on->monitor)}}
                                              : nlohmann::json(nullptr)},
                      {"steps", steps}};
  if (save)
    if (Status st = store.save(p); !st) return st.error();
  if (a.json) cli::print_json(j);
  else {
    std::printf("dominant eye %s%s, sigma_d %.1f, sigma_nd %.1f; validation %d/%d identical pairs right -> %s\n",
                eye_name(r.dominant_eye), r.dominant_consistent ? "" : " (trials disagreed)", r.sigma_uniform,
                r.sigma_non_dominant, r.validation_trials - r.validation_failures, r.validation_trials,
                save ? ("saved to profile " + name).c_str() : a.dry_run ? "not saved (dry run)" : "NOT saved");
    if (judged_on)
      std::printf("judged on %s: the %dx%d frames shown at %dx%d (%.2fx%s)\n",
                  judged_on->monitor.empty() ? "a desktop window" : ("monitor " + judged_on->monitor).c_str(),
                  judged_on->frame_width, judged_on->frame_height, judged_on->shown_width, judged_on->shown_height,
                  judged_on->scale(), judged_on->scale() < 0.99 ? ": shrunk, sigma is likely too high" : "");
    if (gaze)
      std::printf("gaze in the validation trials (%d targets): accuracy L %.3f R %.3f deg, precision RMS-S2S "
                  "L %.3f R %.3f deg, STD L %.3f R %.3f deg, data loss L %.1f%% R %.1f%%\n",
                  gaze->targets, gaze->channels[0].accuracy_deg, gaze->channels[1].accuracy_deg,
                  gaze->channels[0].rms_s2s_deg, gaze->channels[1].rms_s2s_deg, gaze->channels[0].std_deg,
                  gaze->channels[1].std_deg, gaze->channels[0].data_loss_pct, gaze->channels[1].data_loss_pct);
  }
  if (!r.passed())
    return bad_input("calibration rejected: " + std::to_string(r.validation_failures) + " of " +
                     std::to_string(r.validation_trials) +
                     " identical pairs were answered 'different'; nothing was saved, please run it again");
  return {};
}

}  // namespace foveal::cmd

#pragma once
// A participant's run through a study plan (docs/study.md): takes one response per
// trial, checks validation trials, pauses after a failed one and gives up on the
// participant past the allowed errors. The headset window and the scripted mode
// (--answers) drive the same session.
#include <optional>
#include <string>
#include <vector>

#include "foveal/core/error.hpp"
#include "foveal/study/study_design.hpp"

namespace foveal {

/// What the participant pressed: 2AFC 1 (the first presentation) or 2 (the second);
/// score 1 (very different from full resolution) to 5 (no difference).
struct StudyResponse {
  int key = 0;
  std::optional<double> response_s;  ///< from the end of the second presentation
};

/// The longest response time a script may give (an hour).
inline constexpr double kMaxResponseSeconds = 3600.0;

/// "1".."5", optionally with the response time in seconds, 0 to kMaxResponseSeconds: "2@0.84".
Result<StudyResponse> parse_study_response(const std::string& word);

struct TrialResult {
  PlannedTrial trial;
  StudyResponse response;
  bool chose_a = false;         ///< 2AFC
  int score = 0;                ///< score design
  bool validation_failed = false;
};

class StudySession {
 public:
  StudySession(StudyOptions o, std::vector<PlannedTrial> plan);
  const StudyOptions& options() const { return o_; }
  bool done() const { return discarded_ || next_ >= plan_.size(); }
  /// The trial to present now; valid while !done().
  const PlannedTrial& trial() const { return plan_[next_]; }
  /// Feeds the response to trial(). Errors: a key outside the design's range, or done().
  Status respond(const StudyResponse& r);
  /// A failed validation trial asks for a pause before the next trial: true until resume().
  bool pause_requested() const { return pause_requested_; }
  void resume() { pause_requested_ = false; }

  const std::vector<TrialResult>& results() const { return results_; }
  std::size_t planned() const { return plan_.size(); }
  int validation_trials() const { return validation_trials_; }
  int validation_failures() const { return validation_failures_; }
  int pauses() const { return pauses_; }
  /// More failed validation trials than options().max_validation_errors: the run stopped.
  bool discarded() const { return discarded_; }

 private:
  StudyOptions o_;
  std::vector<PlannedTrial> plan_;
  std::vector<TrialResult> results_;
  std::size_t next_ = 0;
  int validation_trials_ = 0, validation_failures_ = 0, pauses_ = 0;
  bool pause_requested_ = false, discarded_ = false;
};

/// The trials CSV `foveal study stats` reads (docs/study.md), one row per answered trial.
std::string study_trials_csv(const StudySession& s);

}  // namespace foveal

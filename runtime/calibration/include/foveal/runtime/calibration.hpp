#pragma once
// The in-headset calibration as a state machine (docs/calibration.md): the Miles test
// for the dominant eye, the EFR slider test for sigma_UF then sigma_NF, and validation
// trials with identical pairs. The window mode and the scripted mode (--answers) drive
// the same machine; it knows nothing of rendering or input devices.
#include <string>
#include <vector>

#include "foveal/core/error.hpp"
#include "foveal/core/gaze_sample.hpp"

namespace foveal {

enum class Answer { left, right, same, different };
const char* answer_name(Answer a);
/// "left", "right", "same", "different" (also l, r, s, d).
Result<Answer> parse_answer(const std::string& word);

enum class CalibrationStage { dominant_eye, sigma_uniform, sigma_non_dominant, validation, done };
const char* calibration_stage_name(CalibrationStage s);

/// What to show and ask now.
struct CalibrationPrompt {
  CalibrationStage stage = CalibrationStage::dominant_eye;
  int trial = 0;                 ///< 0-based within the stage
  /// Miles test: the eye that sees the frame and target (the other sees black).
  Eye shown_eye = Eye::left;
  /// Comparisons: the test image's per-eye sigma, shown against full resolution
  /// (sigma 1). Validation trials show full against full.
  double sigma_left = 1.0, sigma_right = 1.0;
  bool identical = false;        ///< a validation trial: the correct answer is "same"
  std::string question;          ///< what to ask the user
};

struct CalibrationResult {
  Eye dominant_eye = Eye::right;
  bool dominant_consistent = true;  ///< every Miles trial agreed
  double sigma_uniform = 2.0;       ///< sigma_UF: both eyes, no visible difference
  double sigma_non_dominant = 3.0;  ///< sigma_NF: non-dominant eye, still no imbalance
  int validation_trials = 0;
  int validation_failures = 0;      ///< "different" answered for identical pairs
  bool passed() const { return validation_failures * 3 <= validation_trials; }  // <= 1 in 3 wrong
};

struct CalibrationOptions {
  int miles_trials = 3;          ///< odd, so a majority exists
  double sigma_start = 3.0;      ///< the slider test's start (EFR protocol)
  double sigma_step = 0.2;
  double sigma_min = 1.0, sigma_max = 6.0;
  int validation_trials = 3;
  Status validate() const;
};

class Calibration {
 public:
  explicit Calibration(CalibrationOptions o = {});
  const CalibrationPrompt& prompt() const { return prompt_; }
  bool done() const { return prompt_.stage == CalibrationStage::done; }
  /// Feeds the user's answer to the current prompt. Errors: an answer that does not fit
  /// the prompt (same/different to a Miles trial, left/right to a comparison), or any
  /// answer once done.
  Status answer(Answer a);
  /// Valid once done().
  const CalibrationResult& result() const { return result_; }

 private:
  void enter_stage(CalibrationStage s);
  void set_compare(double left, double right);

  CalibrationOptions o_;
  CalibrationPrompt prompt_;
  CalibrationResult result_;
  int votes_right_ = 0, votes_left_ = 0;
  double sigma_ = 3.0;  // the slider's current value
};

}  // namespace foveal

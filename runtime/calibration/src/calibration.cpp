#include "foveal/runtime/calibration.hpp"

#include <algorithm>
#include <cmath>

namespace foveal {

namespace {
// Slider values land on the step grid (3.0, 2.8, ...), not on accumulated rounding.
double on_grid(double v) { return std::round(v * 1000.0) / 1000.0; }
}  // namespace

const char* answer_name(Answer a) {
  switch (a) {
    case Answer::left: return "left";
    case Answer::right: return "right";
    case Answer::same: return "same";
    case Answer::different: return "different";
  }
  return "?";
}

Result<Answer> parse_answer(const std::string& w) {
  if (w == "left" || w == "l") return Answer::left;
  if (w == "right" || w == "r") return Answer::right;
  if (w == "same" || w == "s") return Answer::same;
  if (w == "different" || w == "d") return Answer::different;
  return bad_input("'" + w + "' is not an answer (left, right, same, different)");
}

const char* calibration_stage_name(CalibrationStage s) {
  switch (s) {
    case CalibrationStage::dominant_eye: return "dominant_eye";
    case CalibrationStage::sigma_uniform: return "sigma_uniform";
    case CalibrationStage::sigma_non_dominant: return "sigma_non_dominant";
    case CalibrationStage::validation: return "validation";
    case CalibrationStage::done: return "done";
  }
  return "?";
}

Status CalibrationOptions::validate() const {
  if (miles_trials < 1 || miles_trials % 2 == 0) return bad_input("calibration: miles_trials must be odd and >= 1");
  if (!(sigma_step > 0) || !(sigma_min >= 1.0) || !(sigma_max > sigma_min) || !(sigma_start >= sigma_min) ||
      !(sigma_start <= sigma_max))
    return bad_input("calibration: need 1 <= sigma_min <= sigma_start <= sigma_max and sigma_step > 0");
  if (validation_trials < 0) return bad_input("calibration: validation_trials must be >= 0");
  return {};
}

Calibration::Calibration(CalibrationOptions o) : o_(o) { enter_stage(CalibrationStage::dominant_eye); }

void Calibration::set_compare(double left, double right) {
  prompt_.sigma_left = left;
  prompt_.sigma_right = right;
  prompt_.identical = false;
}

void Calibration::enter_stage(CalibrationStage s) {
  prompt_ = CalibrationPrompt{};
  prompt_.stage = s;
  switch (s) {
    case CalibrationStage::dominant_eye:
      prompt_.shown_eye = Eye::left;
      prompt_.question = "Frame the target with both eyes open; now only one eye sees it. Which eye keeps the "
                         "target inside the frame? (left/right)";
      break;
    case CalibrationStage::sigma_uniform:
      sigma_ = o_.sigma_start;
      set_compare(sigma_, sigma_);
      prompt_.question = "Is the test image different from full resolution? (same/different)";
      break;
    case CalibrationStage::sigma_non_dominant: {
      sigma_ = result_.sigma_uniform;
      const double nd = on_grid(std::min(sigma_ + o_.sigma_step, o_.sigma_max));
      sigma_ = nd;
      const bool left_dominant = result_.dominant_eye == Eye::left;
      set_compare(left_dominant ? result_.sigma_uniform : nd, left_dominant ? nd : result_.sigma_uniform);
      prompt_.question = "Do the two eyes look unbalanced, or different from full resolution? (same/different)";
      break;
    }
    case CalibrationStage::validation:
      prompt_.sigma_left = prompt_.sigma_right = 1.0;
      prompt_.identical = true;
      prompt_.question = "Is the test image different from full resolution? (same/different)";
      break;
    case CalibrationStage::done: break;
  }
}

Status Calibration::answer(Answer a) {
  const bool eye_answer = a == Answer::left || a == Answer::right;
  switch (prompt_.stage) {
    case CalibrationStage::done: return bad_input("calibration is already complete");
    case CalibrationStage::dominant_eye: {
      if (!eye_answer) return bad_input("the dominant-eye test asks for left or right");
      (a == Answer::right ? votes_right_ : votes_left_)++;
      if (++prompt_.trial < o_.miles_trials) {
        prompt_.shown_eye = prompt_.trial % 2 ? Eye::right : Eye::left;
        return {};
      }
      result_.dominant_eye = votes_right_ > votes_left_ ? Eye::right : Eye::left;
      result_.dominant_consistent = votes_right_ == 0 || votes_left_ == 0;
      enter_stage(CalibrationStage::sigma_uniform);
      return {};
    }
    case CalibrationStage::sigma_uniform: {
      if (eye_answer) return bad_input("the slider test asks for same or different");
      if (a == Answer::same || sigma_ <= o_.sigma_min) {
        result_.sigma_uniform = a == Answer::same ? sigma_ : o_.sigma_min;
        enter_stage(CalibrationStage::sigma_non_dominant);
        return {};
      }
      sigma_ = on_grid(std::max(sigma_ - o_.sigma_step, o_.sigma_min));
      set_compare(sigma_, sigma_);
      ++prompt_.trial;
      return {};
    }
    case CalibrationStage::sigma_non_dominant: {
      if (eye_answer) return bad_input("the slider test asks for same or different");
      if (a == Answer::different || sigma_ >= o_.sigma_max) {
        // The last level that still looked the same.
        result_.sigma_non_dominant = a == Answer::different ? on_grid(sigma_ - o_.sigma_step) : o_.sigma_max;
        result_.sigma_non_dominant = std::max(result_.sigma_non_dominant, result_.sigma_uniform);
        if (o_.validation_trials > 0) enter_stage(CalibrationStage::validation);
        else enter_stage(CalibrationStage::done);
        return {};
      }
      sigma_ = on_grid(std::min(sigma_ + o_.sigma_step, o_.sigma_max));
      const bool left_dominant = result_.dominant_eye == Eye::left;
      set_compare(left_dominant ? result_.sigma_uniform : sigma_, left_dominant ? sigma_ : result_.sigma_uniform);
      ++prompt_.trial;
      return {};
    }
    case CalibrationStage::validation: {
      if (eye_answer) return bad_input("a validation trial asks for same or different");
      ++result_.validation_trials;
      if (a == Answer::different) ++result_.validation_failures;
      if (++prompt_.trial >= o_.validation_trials) enter_stage(CalibrationStage::done);
      return {};
    }
  }
  return {};
}

}  // namespace foveal

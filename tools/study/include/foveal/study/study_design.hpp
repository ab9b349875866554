#pragma once
// The trials of a perception study (docs/study.md, "Running a study"): the RMFR paper's
// two-alternative forced choice between two rendering conditions, or the EFR paper's
// random test scoring conditions against full resolution, with validation trials, in a
// random order that a seed fixes. Knows nothing of rendering or input devices.
#include <cstdint>
#include <string>
#include <vector>

#include "foveal/core/error.hpp"

namespace foveal {

/// One way of rendering both eyes: a method, the dominant and non-dominant eye's level
/// (equal for the 2AFC's uniform conditions), and RMFR's f (a fraction of each axis).
struct StudyCondition {
  std::string method = "full";
  double sigma_d = 1.0, sigma_nd = 1.0;
  double f = 0.3;
  bool operator==(const StudyCondition&) const = default;
  bool uniform() const { return sigma_d == sigma_nd; }
  /// "full", "rmfr sigma=2.6 f=0.3", "rmfr sigma_d=2 sigma_nd=3 f=0.3".
  std::string label() const;
};

/// A level or f as labels and the trials CSV write it: the shortest form, "2.6", "3".
std::string level_text(double v);

/// METHOD[:SIGMA[/SIGMA_ND]][:F], e.g. "full", "kfr:2.6", "rmfr:2.6:0.25", "rmfr:2/3".
/// The method name is not checked here (the renderer knows its methods). Errors name `what`.
Result<StudyCondition> parse_study_condition(const std::string& spec, const std::string& what);

enum class StudyDesign { two_afc, score };
const char* study_design_name(StudyDesign d);  ///< "2afc", "score"

struct StudyOptions {
  StudyDesign design = StudyDesign::two_afc;
  std::string participant = "p01";
  std::vector<std::string> scenes;  ///< at least one
  /// 2AFC: every pair of these is compared. Score: each is scored against full resolution.
  std::vector<StudyCondition> conditions;
  int repeats = 3;                 ///< per pair (2AFC) or condition (score), per scene
  double validation_share = 0.3;   ///< of all trials (the EFR paper's 30%), in [0, 0.9]
  /// 2AFC validation: full resolution against this, where `full` is the right answer.
  StudyCondition validation_condition{"rmfr", 6.0, 6.0, 0.3};
  /// Score validation: identical frames; a score below this fails (5 = no difference).
  int validation_min_score = 4;
  /// More failed validation trials than this discard the participant's data.
  int max_validation_errors = 2;
  double present_s = 2.0, blank_s = 0.75;  ///< each presentation; the black between
  std::uint64_t seed = 0;          ///< 0: derived from the participant id (study_seed)
  Status validate() const;
};

/// The seed a study uses: options.seed, or a hash (FNV-1a 64) of the participant id.
std::uint64_t study_seed(const StudyOptions& o);

struct PlannedTrial {
  int index = 0;  ///< 1-based, in presentation order
  std::string scene;
  StudyCondition a, b;      ///< 2AFC: the two conditions; score: a = full, b = the one scored
  bool b_first = false;     ///< which is presented first
  bool validation = false;  ///< 2AFC: b is the validation condition; score: b = full as well
};

/// Every trial in presentation order: the test trials (pairs or conditions x scenes x
/// repeats) and round(share / (1 - share) x tests) validation trials spread over the
/// scenes, shuffled together; each trial's presentation order drawn separately. The same
/// options give the same plan on every machine (own Fisher-Yates on mt19937_64).
Result<std::vector<PlannedTrial>> plan_study(const StudyOptions& o);

}  // namespace foveal

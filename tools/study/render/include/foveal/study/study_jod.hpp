#pragma once
// The JOD the native FovVideoVDP predicts for each condition of a study (docs/study.md,
// "Predicted JOD"): the condition's frame against full resolution on the same scene, each
// eye foveated at the study's fixation (the centre of each eye), on the study's display
// model at the study's size, so the participants' answers can be read beside it.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/bench/bench_jod.hpp"
#include "foveal/study/study_design.hpp"
#include "foveal/study/study_frames.hpp"

namespace foveal {

struct ConditionJod {
  std::string scene;
  StudyCondition condition;
  bench::StereoJod jod;  ///< left, right, and both eyes' (the mean pooled difference's)
};

struct StudyJod {
  std::vector<ConditionJod> rows;  ///< per scene (in the options' order) x condition
  nlohmann::json settings;         ///< how they were scored (bench::jod_settings) and what it cost
};

/// Renders full and every condition of `o` on every scene through `frames` (whose
/// compositor is width x height on `model`) and scores each condition against full.
Result<StudyJod> predict_study_jod(StudyFrames& frames, const StudyOptions& o, const DisplayModel& model);

/// conditions.csv: scene,condition,method,sigma_d,sigma_nd,f,predicted_jod,predicted_jod_left,predicted_jod_right.
std::string study_conditions_csv(const StudyJod& j);

/// The mean over scenes of the both-eye predicted JOD of the condition labelled `label`,
/// either as StudyCondition::label() (score trials) or, for a uniform condition, as
/// `study stats` labels a 2AFC side ("rmfr sigma=2.6 f=0.3", "full sigma=1 f="); null
/// when no condition has it.
nlohmann::json predicted_jod_of(const StudyJod& j, const std::string& label);

}  // namespace foveal

#pragma once
// What `foveal study run` does once its options are parsed (docs/study.md): plans the
// trials, shows them in the headset window or scripted from an answers file (headless),
// predicts each condition's JOD, and writes trials.csv, conditions.csv and summary.json.
#include <string>

#include "foveal/core/error.hpp"
#include "foveal/study/study_design.hpp"

namespace foveal {

/// How the study is run and where it goes, beside the study's own options.
struct StudyRunSettings {
  std::string answers;     ///< scripted mode's answers file; empty: the headset window
  std::string frames_out;  ///< scripted mode: save each presentation as DIR/trial_NNN_P.png
  std::string monitor;     ///< headset mode: fullscreen on the monitor whose name contains this
  std::string size;        ///< output WxH (even width); empty: the display model's
  std::string dominant = "right";  ///< the participant's dominant eye, "left" or "right"
  std::string out;         ///< directory for trials.csv, conditions.csv and summary.json
  bool json = false;       ///< print the summary as JSON
  bool no_jod = false;     ///< leave out each condition's predicted JOD
};

/// Runs the study of `options` (validated) to its end and writes its files; prints the
/// summary. Errors: no display, the participant quit, a bad answers file, GL or file
/// failures; a discarded participant is bad_input after the summary is written.
Status run_study(const StudyOptions& options, const StudyRunSettings& a);

}  // namespace foveal

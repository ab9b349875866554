#pragma once
// `foveal study run`'s in-headset mode: presents each trial in a GLFW window (fullscreen
// on the HMD's monitor) and takes the responses from the keyboard or a gamepad.
#include "foveal/render/window.hpp"
#include "foveal/study/study_session.hpp"
#include "foveal/study/study_frames.hpp"

namespace foveal {

/// The pause after a failed validation trial lasts at least this long, then waits for
/// Enter, Space or the gamepad's Start/A.
constexpr double kStudyPauseMinS = 5.0;

/// Runs `session` to its end (done or discarded). Errors: the participant or operator
/// quit (Esc or closing the window: bad_input, nothing is written), GL failures.
Status run_study_window(StudySession& session, StudyFrames& frames, render::Window& window);

}  // namespace foveal

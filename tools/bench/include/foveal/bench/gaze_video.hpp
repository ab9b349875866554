#pragma once
// bench --gaze --gaze-video N: per log, method and level, N consecutive frames of the
// rendered stream scored as one video with FovVideoVDP's temporal channels, the camera
// on the recorded head pose per frame (docs/bench.md, "Gaze-driven evaluation").
#include <cstddef>
#include <functional>
#include <vector>

#include "foveal/bench/bench_jod.hpp"
#include "foveal/bench/gaze_timeline.hpp"
#include "foveal/core/error.hpp"
#include "foveal/image/image.hpp"

namespace foveal::bench {

/// gaze_video.csv's header (docs/bench.md).
inline constexpr const char* kGazeVideoColumns =
    "scene,log,display,method,gaze,sigma_d,sigma_nd,frames,blink_frames,fps,head_speed_deg_s,jod_left,jod_right,jod";

/// The head's mean angular speed over a sequence of consecutive frames: the angles between
/// successive frames' head orientations, summed, over the sequence's duration at `fps`
/// (deg/s). 0 with a static head or fewer than two frames.
double mean_head_speed_deg_s(const std::vector<GazeFrame>& frames, double fps);

struct GazeVideoScore {
  std::size_t frames = 0;        ///< frames in the video
  std::size_t blink_frames = 0;  ///< frames left out: a blink or dropout at display time
  StereoJod jod;
};

/// Frame k's side-by-side image: the reference (full, the frame's head) or the test.
using SequenceImage = std::function<Result<image::Image>(std::size_t k)>;

/// Scores frames[k]'s test against its reference as one video at `fps`, each eye fixating
/// its true gaze at display time. A frame in a blink is left out, as in the stills: the
/// viewer sees nothing then, and the video goes on with the next frame seen. Errors: no
/// frame outside a blink.
Result<GazeVideoScore> score_gaze_video(StereoJodScorer& jod, double fps, const std::vector<GazeFrame>& frames,
                                        const SequenceImage& reference, const SequenceImage& test);

}  // namespace foveal::bench

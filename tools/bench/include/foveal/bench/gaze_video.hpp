#pragma once
// bench --gaze --gaze-video N: per log, method and level, N consecutive frames of the
// rendered stream scored as one video with FovVideoVDP's temporal channels, the camera
// on the recorded head pose per frame (docs/bench.md, "Gaze-driven evaluation").
#include <cmath>
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "foveal/bench/bench_jod.hpp"
#include "foveal/bench/gaze_timeline.hpp"
#include "foveal/core/display_model.hpp"
#include "foveal/core/error.hpp"
#include "foveal/image/image.hpp"

namespace foveal::bench {

/// gaze_video.csv's header (docs/bench.md): the first columns as before temporal
/// accumulation, then each point's accumulation, cost and its frames after saccades.
inline constexpr const char* kGazeVideoColumns =
    "scene,log,display,method,gaze,sigma_d,sigma_nd,frames,blink_frames,fps,head_speed_deg_s,jod_left,jod_right,jod,"
    "temporal,shaded_samples,cost,gpu_ms,cpu_ms,saccades,post_saccade_frames,post_saccade_fpsnr_mean,post_saccade_jod_mean,"
    "post_saccade_fpsnr_worst_vs_off,post_saccade_jod_worst_vs_off";
/// gaze_video_frames.csv's header: one row per frame of each video (JOD on the frames
/// after a saccade only: a still JOD per frame would double the video's cost).
inline constexpr const char* kGazeVideoFrameColumns =
    "scene,log,method,gaze,sigma_d,temporal,frame,t_display_s,true_step_deg,post_saccade,fpsnr_db,patch_psnr_db,jod_left,jod_right,jod";

/// A frame whose true gaze moved faster than this since the previous frame seen starts a
/// saccade: velocity-threshold (I-VT) detectors use 30-100 deg/s; at 100 neither
/// fixational drift, pursuit nor the recordings' noise passes it.
inline constexpr double kSaccadeDegPerS = 100.0;
/// The frames "after a saccade": its onset and this many more (67 ms at 90 Hz: the gaze
/// filter's lag, a frame of latency, and the accumulation's history refilling).
inline constexpr std::size_t kPostSaccadeFrames = 6;

/// Where a video's saccades are, from the recording's true gazes at display time.
struct SaccadeWindows {
  std::vector<double> step_deg;  ///< per frame: the larger eye's true-gaze step since the previous frame seen (0: first, blink)
  std::vector<bool> post;        ///< per frame: an onset or within kPostSaccadeFrames after one (never a blink)
  std::size_t onsets = 0;
};
SaccadeWindows find_saccades(const std::vector<GazeFrame>& frames, const DisplayModel& model, double fps);

/// One frame of a video against its reference, at the true gaze.
struct VideoFrameFigures {
  double fpsnr_db = 0, patch_psnr_db = 0;  ///< both eyes' FPSNR; the lower eye's fovea patch
  std::optional<StereoJod> jod;            ///< a still's JOD, where it was scored
};

/// A video's frames after saccades, and against the same frames without accumulation.
struct PostSaccade {
  std::size_t frames = 0;
  double fpsnr_mean = NAN, jod_mean = NAN;  ///< over them (JOD over those scored)
  /// The lowest difference this run minus `off` over them: negative where a frame after a
  /// saccade is worse than without accumulation. NaN without `off`.
  double fpsnr_worst_vs_off = NAN, jod_worst_vs_off = NAN;
};
/// `figures` and `off` are per frame of the video (the frames `windows.post` marks are read).
PostSaccade post_saccade(const SaccadeWindows& windows, const std::vector<VideoFrameFigures>& figures,
                         const std::vector<VideoFrameFigures>* off);

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

/// Called with each frame seen, its reference and test, after it joined the video.
using FrameCheck = std::function<Status(std::size_t k, const image::Image& reference, const image::Image& test)>;

/// Scores frames[k]'s test against its reference as one video at `fps`, each eye fixating
/// its true gaze at display time. A frame in a blink is left out, as in the stills: the
/// viewer sees nothing then, and the video goes on with the next frame seen. The test
/// frames are made in order, one each, so a renderer's history runs through the video.
/// Errors: no frame outside a blink; what `check` returns.
Result<GazeVideoScore> score_gaze_video(StereoJodScorer& jod, double fps, const std::vector<GazeFrame>& frames,
                                        const SequenceImage& reference, const SequenceImage& test, const FrameCheck& check = {});

}  // namespace foveal::bench

#pragma once
// The frames a gaze-driven bench run scores (docs/bench.md, "Gaze-driven evaluation"):
// a recorded log through the runtime's gaze pipeline, frames at a fixed rate, and for
// each frame the fovea the runtime would have rendered with and where the eyes really
// were when the frame reached the display.
#include <array>
#include <cstddef>
#include <vector>

#include <glm/vec2.hpp>

#include "foveal/core/display_model.hpp"
#include "foveal/core/error.hpp"
#include "foveal/core/gaze_sample.hpp"
#include "foveal/core/pose_source.hpp"
#include "foveal/runtime/filter_config.hpp"

namespace foveal::bench {

struct GazeTimelineOptions {
  double fps = 90;          ///< frame rate of the stream
  double latency_ms = -1;   ///< frame start -> display; < 0: one frame period
  double start_s = 1.0;     ///< first frame this long after the first sample (the filter settles)
  int frames = 24;          ///< frames scored (at most)
  /// Which frames: even (every stride-th of the stream), spread (true gazes spread
  /// evenly in eccentricity from the optical centre up to spread_max_deg: one frame per
  /// equal-width bin, the one nearest the bin's middle; an empty bin gives no frame) or
  /// consecutive (the stream's first `frames` frames, for a video: --gaze-video).
  enum class Pick { even, spread, consecutive } pick = Pick::even;
  double spread_max_deg = 30;
  bool head_recorded = false;
};

/// One scored frame. Points are normalised viewport coordinates (origin top-left, y down).
struct GazeFrame {
  std::size_t index = 0;            ///< frame number in the stream (time = start + index / fps)
  TimeNs t_render = 0, t_display = 0;
  TimeNs t_sample = 0;              ///< the sample whose filtered fovea the frame used
  std::array<glm::dvec2, 2> fovea{};  ///< filtered, as foveald's exchange held it at t_render
  std::array<glm::dvec2, 2> truth{};  ///< raw recorded gaze at t_display (valid unless `blink`)
  double truth_ecc_deg = 0;         ///< mean of the eyes' true gazes' angles from their optical centres
  bool blink = false;               ///< an eye has no valid raw direction at t_display
  PoseAt head;                      ///< the head pose foveald would use (at t_sample)
};

struct GazeTimeline {
  std::vector<GazeFrame> frames;
  std::size_t stream_frames = 0;  ///< frames of the whole stream at `fps`
  std::size_t stride = 1;         ///< every stride-th frame of the stream is scored (Pick::even)
  double latency_ms = 0;          ///< the latency used
};

/// Runs `samples` through GazePipeline(model, filter) sample by sample (as foveald's gaze
/// thread does) and picks the frames. Errors (bad_input): fewer than 2 samples, a stream
/// too short for one frame after `start_s`, bad options, a spread pick that finds no
/// frame with both eyes tracked.
Result<GazeTimeline> build_gaze_timeline(const std::vector<GazeSample>& samples, const DisplayModel& model,
                                         const FilterConfig& filter, const GazeTimelineOptions& o);

}  // namespace foveal::bench

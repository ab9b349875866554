#pragma once
// foveal bench --gaze: every method × level scored frame by frame on a recorded gaze log,
// the fovea where the runtime would have put it and the metric where the eyes really
// were (docs/bench.md, "Gaze-driven evaluation").
#include <string>
#include <utility>
#include <vector>

#include "foveal/image/foveation_plan.hpp"
#include "foveal/perception/jod.hpp"
#include "foveal/render/compositor.hpp"

namespace foveal::bench {

/// The options only a --gaze run has.
struct GazeBenchOptions {
  std::vector<std::string> logs;  ///< native gaze logs (after `foveal import`)
  std::string head;               ///< recorded | static; empty: recorded when the log has a pose
  std::string display;            ///< display-model file or name under data/display; empty: Vive Pro Eye
  double fps = 90, latency_ms = -1, start_s = 1.0;
  int frames = 24;
  int video_frames = 0;           ///< --gaze-video N: N consecutive frames scored as a video per log, method and level; 0: none
  std::string pick = "even";      ///< even | spread (gaze_timeline.hpp)
  double spread_max_deg = 30;
  double efr_ratio = 1.5;         ///< σ_nd / σ_d (dominant right eye)
  double patch_deg = 5.0, patch_margin_db = 3.0;
  double inset_deg = 0.0;         ///< inset methods: the inner view's half-extent (degrees); 0: 35% of the view per axis
  bool size_given = false;        ///< --size given: it replaces the model's pixels (its field of view stays)
};

/// What the bench's common options say.
struct GazeBenchSweep {
  std::vector<std::string> scenes;
  std::vector<render::Method> methods;  ///< without full (the reference)
  std::vector<double> sigmas;
  std::pair<int, int> size{2880, 1600};
  std::string out;
  int timed_frames = 3, warmup = 1;
  double fx = 0.3, fy = 0.3;
  bool no_png = false, json = false;
  std::string shard;  ///< --shard K/N (empty: the whole sweep; bench_sweep.hpp)
  std::string sweep;  ///< the options that define the sweep, for the shard file
  bool jod = true;    ///< JOD per frame at the true gaze (bench_jod.hpp); false: --no-jod
  perception::Photometry light;  ///< the panel's luminance for JOD (--peak, --black)
  render::Pipeline pipeline = render::Pipeline::visibility;  ///< every frame's, the references' too
  std::vector<bool> temporal{false};  ///< --gaze-video's accumulation off and/or on (bench_flicker.hpp's temporal_values)
  render::BlendAt blend_at = render::BlendAt::output;  ///< --blend-at, every foveated frame (FrameParams::blend_at)
};

/// Runs the gaze-driven evaluation; returns the exit code.
int run_gaze_bench(const GazeBenchOptions& g, const GazeBenchSweep& s);

}  // namespace foveal::bench

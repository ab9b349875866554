#pragma once
// foveal bench --flicker: temporal stability of each method and pipeline in the
// periphery, with the fovea following a real recording (or fixed) and the camera still or
// moving along a path (camera_path.hpp). Flicker is the frame-to-frame change that the
// full-resolution reference, rendered along the same path, does not have
// (docs/stability.md, "Temporal stability").
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "foveal/bench/bench_jod.hpp"
#include "foveal/bench/bench_sweep.hpp"
#include "foveal/bench/camera_path.hpp"
#include "foveal/core/error.hpp"
#include "foveal/render/compositor.hpp"

namespace foveal::bench {

/// Where the fovea is in a flicker run: each sample's raw gaze, the gaze filter's output,
/// or fixed at --fovea.
enum class FlickerGaze { raw, filtered, fixed };
const char* flicker_gaze_name(FlickerGaze g);

struct FlickerOptions {
  std::string log;  ///< gaze log; empty: the bundled recording
  int frames = 48;
  double sigma = 2.0, fx = 0.3, fy = 0.3;  ///< sigma: the dominant (right) eye's
  double sigma_nd = 0;  ///< the other eye's (EFR); 0: sigma
  std::pair<double, double> fovea{0.5, 0.5};  ///< FlickerGaze::fixed's
  std::vector<CameraPath> cameras{CameraPath{}};
  double pivot_m = 0;  ///< > 0: the orbit's and dolly's pivot distance; 0: default_pivot_m
  bool fill = false;   ///< start where the scene's bounding sphere fills the view
  std::vector<FlickerGaze> gazes{FlickerGaze::raw, FlickerGaze::filtered};
  std::vector<render::Pipeline> pipelines{render::Pipeline::gbuffer};
  /// false: every pipeline is scored against full through the G-buffer pipeline; true:
  /// against full through itself (only what foveation adds, not the pipelines' difference).
  bool own_reference = false;
  /// Temporal accumulation off and/or on (FrameParams::temporal), in this order: a point
  /// where it applies (render::temporal_applies) runs once per value, any other once, off.
  std::vector<bool> temporal{false};
  render::BlendAt blend_at = render::BlendAt::output;  ///< --blend-at, every foveated frame (FrameParams::blend_at)
};

/// The parsed form of the comma lists `--camera-path`, `--flicker-gaze` and
/// `--flicker-pipelines` (empty: `fallback`); errors name the option.
Result<std::vector<CameraPath>> parse_camera_paths(const std::string& list);
Result<std::vector<FlickerGaze>> parse_flicker_gazes(const std::string& list);
Result<std::vector<render::Pipeline>> parse_flicker_pipelines(const std::string& list, render::Pipeline fallback);
/// `--temporal`'s comma list of off and on, off first whatever the order given.
Result<std::vector<bool>> parse_temporal_list(const std::string& list);
/// The values of `temporal` a point of method m through pipeline p runs with.
std::vector<bool> temporal_values(const std::vector<bool>& temporal, render::Method m, render::Pipeline p);

/// Points of the sweep one scene's flicker runs take: camera × pipeline × method (full
/// first) × its temporal values × gaze.
std::size_t flicker_points(const FlickerOptions& o, const std::vector<render::Method>& methods_without_full);

/// Renders every point on the scene `spec` and adds its rows (flicker.csv and the list
/// "flicker") through `rows`; `tick` after each point. With `jod`, each point's frames
/// are also scored as a video (the columns kFlickerJodColumns), which keeps the
/// reference's frames whole in memory (W·H·4 bytes each).
Status run_flicker(const FlickerOptions& o, render::Compositor& comp, const std::vector<render::Method>& methods_without_full,
                   const std::string& spec, bench::SweepRows& rows, const std::function<void()>& tick, StereoJodScorer* jod = nullptr);

/// flicker.csv's header (`temporal` after the columns it came after); with JOD,
/// kFlickerJodColumns follow.
extern const char* const kFlickerColumns;
inline constexpr const char* kFlickerJodColumns = ",jod_left,jod_right,jod";

}  // namespace foveal::bench

#pragma once
// foveal bench: every method at every level against the full reference, on one or more
// scenes: per-pass times, shaded samples, PSNR/SSIM/FPSNR; optional experiments (RMFR f
// grid with the automatic f, rotated patterns, stability, flicker) or, with gaze logs,
// the gaze-driven evaluation; CSV + JSON + charts (docs/bench.md). The options as the
// command line gave them: run_bench checks them, and a message names the option.
#include <optional>
#include <string>
#include <vector>

#include "foveal/bench/bench_gaze.hpp"
#include "foveal/perception/jod.hpp"
#include "foveal/render/compositor.hpp"

namespace foveal::bench {

struct BenchOptions {
  std::vector<std::string> scenes;  ///< glTF files or pattern:NAME; the command puts the bundled Dungeon when none is given
  std::string methods = render::method_names_joined(",");
  render::Pipeline pipeline = render::Pipeline::visibility;  ///< the command parses --pipeline into it
  render::BlendAt blend_at = render::BlendAt::output;  ///< --blend-at, every foveated frame (the full reference blends at output)
  std::string sigmas = "1.4:2.8:0.2";
  std::string fovea = "0.5,0.5";
  std::string size = "2880x1600";
  std::string out;
  int frames = 3, warmup = 1;
  double fx = 0.3, fy = 0.3;
  bool f_grid = false, rotation = false, stability = false, flicker = false, no_png = false, json = false;
  bool no_jod = false;  ///< leave the JOD columns out (bench_jod.hpp: ~0.3 s a 2880x1600 frame on 2 cores)
  perception::Photometry light;  ///< --peak, --black: the panel's luminance for JOD (metrics --jod's defaults)
  std::string flicker_log;  ///< empty: the bundled recording
  int flicker_frames = 48;
  std::string camera_paths = "static", flicker_gaze = "raw,filtered", flicker_pipelines;  ///< bench_flicker.hpp
  std::string flicker_reference = "shared";
  std::string temporal = "off";  ///< --temporal: off, on or both (--flicker and --gaze-video; bench_flicker.hpp)
  std::optional<double> camera_pivot, flicker_sigma_nd;
  bool camera_fill = false;
  double grid_sigma = 2.0;
  std::string grid_values = "0.1:0.5:0.05";
  std::string shard;  ///< K/N; empty: the whole sweep
  GazeBenchOptions gaze;  ///< --gaze runs (bench_gaze.hpp)
};

/// Runs the sweep and writes its outputs into `o.out` (a shard's with `o.shard`);
/// `sweep`: the options that define the grid, which every shard of one sweep shares
/// (shard.json's "sweep"). Reports what is wrong and returns the exit code.
int run_bench(const BenchOptions& o, const std::string& sweep);

}  // namespace foveal::bench

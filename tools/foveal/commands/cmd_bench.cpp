// foveal bench and bench merge: their command lines into the bench's options (tools/bench,
// docs/bench.md); the sweep, its experiments, outputs and merge run there.
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "foveal/bench/bench_merge.hpp"
#include "foveal/bench/bench_run.hpp"
#include "foveal/runtime/cli.hpp"
#include "render/render_args.hpp"

namespace foveal::cmd {

namespace {

struct Args {
  bench::BenchOptions options;
  std::string pipeline = render::kDefaultPipelineName;  ///< parsed into options.pipeline
  std::string blend_at = "output";                        ///< parsed into options.blend_at
};

// --gaze and the options only a gaze-driven run has (bench_gaze.hpp).
void add_gaze_options(CLI::App& sub, bench::GazeBenchOptions& g) {
  CLI::Option* gaze = sub.add_option("--gaze", g.logs, "Gaze-driven evaluation on these native gaze logs (repeatable; docs/bench.md): "
                                   "gaze.csv, gaze_frames.csv, gaze.json, gaze.png");
  sub.add_option("--head", g.head, "Recorded (the log's head pose moves the camera) or static; default: recorded when the log has one")
      ->check(CLI::IsMember({"recorded", "static"}))->needs(gaze);
  sub.add_option("--display", g.display, "Display-model file or name under data/display (default: htc_vive_pro_eye); "
                                         "the size follows it unless --size is given")->needs(gaze);
  sub.add_option("--gaze-fps", g.fps, "Frame rate of the rendered stream (Hz)")->capture_default_str()->needs(gaze);
  sub.add_option("--latency-ms", g.latency_ms, "Frame start to display (ms); default one frame period")->needs(gaze);
  sub.add_option("--gaze-start", g.start_s, "First frame this many seconds into the log")->capture_default_str()->needs(gaze);
  sub.add_option("--gaze-frames", g.frames, "Frames scored per log (at most), picked by --gaze-pick")->capture_default_str()->needs(gaze);
  sub.add_option("--gaze-pick", g.pick, "even: spread evenly over the log's time; spread: true gazes spread evenly in "
                                        "eccentricity from the optical centre up to --gaze-spread-max (one frame per bin)")
      ->capture_default_str()->check(CLI::IsMember({"even", "spread"}))->needs(gaze);
  sub.add_option("--gaze-spread-max", g.spread_max_deg, "Largest eccentricity of --gaze-pick spread (degrees)")
      ->capture_default_str()->check(CLI::Range(0.5, 90.0))->needs(gaze);
  sub.add_option("--gaze-video", g.video_frames, "Also score, per log, method and level, this many consecutive frames from --gaze-start "
                                                "as one video along the recorded head motion: gaze_video.csv (0: no video)")
      ->capture_default_str()->check(CLI::Range(0, 100000))->needs(gaze);
  sub.add_option("--efr-ratio", g.efr_ratio, "Non-dominant (left) eye's level over the dominant's")
      ->capture_default_str()->check(CLI::Range(1.0, 4.0))->needs(gaze);
  sub.add_option("--inset-deg", g.inset_deg, "inset/inset-fixed: the inner view's half-extent in degrees (0: 35% of the view per axis)")
      ->capture_default_str()->check(CLI::Range(0.0, 88.9))->needs(gaze);
  sub.add_option("--patch-deg", g.patch_deg, "Side of the fovea patch around the true gaze (degrees)")
      ->capture_default_str()->check(CLI::Range(0.1, 60.0))->needs(gaze);
  sub.add_option("--patch-margin-db", g.patch_margin_db,
                 "A frame's fovea patch is in error when its PSNR is this far below perfect tracking's (dB)")
      ->capture_default_str()->check(CLI::Range(0.0, 100.0))->needs(gaze);
}

/// The options that define a sweep's grid, as CLI11 writes them (one `name=value` line
/// each, defaults included): every option of `bench` (not its subcommands') but where
/// the output goes and how it is shown.
std::string sweep_options(const CLI::App& sub) {
  std::istringstream in(sub.config_to_str(/*default_also=*/true));
  std::string line, out;
  while (std::getline(in, line)) {
    const std::string key = line.substr(0, line.find('='));
    if (key == "shard" || key == "out" || key == "json" || key == "no-png" || key.empty() || key.find_first_of(".[") != std::string::npos)
      continue;
    out += line + "\n";
  }
  return out;
}

}  // namespace

void add_bench(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<Args>();
  bench::BenchOptions& o = a->options;
  CLI::App* sub = app.add_subcommand("bench", "Every method at every level against full: time, shaded samples, PSNR/SSIM/FPSNR, charts");
  sub->add_option("--scene", o.scenes, "Scenes (repeatable): glTF files or pattern:NAME; default: the bundled Dungeon");
  sub->add_option("--methods", o.methods, "Comma list of methods (" + render::method_names_joined(", ") + ")")->capture_default_str();
  sub->add_option("--pipeline", a->pipeline, "gbuffer or visibility, for every frame including the full reference (docs/rmfr.md)")
      ->check(CLI::IsMember(render::pipeline_names()))
      ->capture_default_str();
  sub->add_option("--blend-at", a->blend_at,
                  "output or samples: where alphaMode BLEND surfaces are shaded in the foveated frames (the full reference: "
                  "output); samples needs --pipeline visibility (docs/rmfr.md, \"Transparency at the kept samples\")")
      ->check(CLI::IsMember(render::blend_at_names()))
      ->capture_default_str();
  sub->add_option("--sigmas", o.sigmas, "Levels: FROM:TO:STEP or a comma list")->capture_default_str();
  sub->add_option("--fovea", o.fovea, "Fovea X,Y of both eyes in [0,1]")->capture_default_str();
  sub->add_option("--size", o.size, "Side-by-side output WxH")->capture_default_str();
  sub->add_option("--frames", o.frames, "Timed frames per point (median)")->capture_default_str();
  sub->add_option("--warmup", o.warmup, "Untimed frames first")->capture_default_str()->check(CLI::Range(0, 100));
  sub->add_option("--fx", o.fx, "RMFR f_x")->capture_default_str();
  sub->add_option("--fy", o.fy, "RMFR f_y")->capture_default_str();
  sub->add_flag("--f-grid", o.f_grid, "Also: RMFR FPSNR over an f_x × f_y grid and the automatic f against it");
  sub->add_option("--grid-values", o.grid_values, "f values of the grid")->capture_default_str();
  sub->add_option("--grid-sigma", o.grid_sigma, "Level of the grid and rotation experiments")->capture_default_str();
  sub->add_flag("--rotation", o.rotation, "Also: rotated stripes 0-180 degrees, FPSNR per method");
  CLI::Option* flicker = sub->add_flag("--flicker", o.flicker,
                "Also, on every scene: periphery flicker against the full reference, the fovea on real gaze (raw, filtered) or fixed, "
                "the camera still or moving, per method and pipeline (docs/stability.md)");
  for (CLI::Option* opt : {
      sub->add_option("--flicker-log", o.flicker_log, "Gaze log for --flicker (default: the bundled recording)"),
      sub->add_option("--flicker-frames", o.flicker_frames, "Frames per flicker run (one per gaze sample)")->capture_default_str()->check(CLI::Range(2, 10000)),
      sub->add_option("--flicker-sigma-nd", o.flicker_sigma_nd,
                      "EFR for --flicker: the left (non-dominant) eye's level; the right eye's is --grid-sigma (default: the same)"),
      sub->add_option("--flicker-gaze", o.flicker_gaze, "Comma list: raw, filtered (the gaze filter's), fixed (at --fovea)")->capture_default_str(),
      sub->add_option("--flicker-pipelines", o.flicker_pipelines, "Comma list of pipelines for --flicker (default: --pipeline)"),
      sub->add_option("--flicker-reference", o.flicker_reference,
                      "shared: every pipeline against full through gbuffer; own: each against full through itself (what foveation adds)")
          ->check(CLI::IsMember({"shared", "own"}))
          ->capture_default_str(),
      sub->add_option("--camera-path", o.camera_paths,
                      "Comma list: static, orbit[:DEG_PER_S] (about a pivot ahead, +-20 deg, default 30 deg/s), dolly[:M_PER_S] (towards the "
                      "pivot and back, half its distance, default a quarter of it per second), recorded (the log's head pose)")
          ->capture_default_str(),
      sub->add_option("--camera-pivot", o.camera_pivot, "Pivot distance ahead of the head, metres (default: from the scene's bounds)"),
      sub->add_flag("--camera-fill", o.camera_fill, "Start the camera where the scene's bounding sphere fills the view (object scenes)")})
    opt->needs(flicker);
  sub->add_option("--temporal", o.temporal,
                  "Comma list of off, on: each --flicker and --gaze-video point whose method and pipeline accumulate (RMFR's kernel, "
                  "visibility pipeline; docs/rmfr.md) with temporal accumulation off and/or on; the rest off")
      ->capture_default_str();
  sub->add_flag("--stability", o.stability, "Also: fovea from the centre to a corner and to a border, patch PSNR and FPSNR per method");
  const CLI::Option* size = sub->get_option("--size");
  add_gaze_options(*sub, o.gaze);
  sub->add_option("--shard", o.shard, "Run only the K-th of N disjoint parts of the sweep (K/N); merge with `bench merge`");
  sub->add_option("--out,-o", o.out, "Output directory (required)");
  sub->add_flag("--no-png", o.no_png, "CSV and JSON only");
  sub->add_flag("--no-jod", o.no_jod, "Leave out the JOD columns (FovVideoVDP, docs/metrics.md: about 0.3 s per 2880x1600 frame on 2 cores)");
  sub->add_option("--peak", o.light.peak_cd_m2, "The panel's peak luminance for JOD, cd/m2 (every experiment; recorded in bench.json's jod)")
      ->capture_default_str();
  sub->add_option("--black", o.light.black_cd_m2, "The panel's black luminance for JOD, cd/m2 (0 < black < peak)")->capture_default_str();
  sub->add_flag("--json", o.json, "Print the results as JSON");
  add_bench_merge(*sub, exit_code);
  sub->callback([a, sub, size, &exit_code] {
    if (sub->got_subcommand("merge")) return;
    auto pipeline = render::parse_pipeline(a->pipeline);
    if (!pipeline) {
      exit_code = cli::report(pipeline.error());
      return;
    }
    bench::BenchOptions run = a->options;
    run.pipeline = *pipeline;
    run.blend_at = *render::parse_blend_at(a->blend_at);  // checked by IsMember
    if (Status s = render::check_blend_at(run.blend_at, run.pipeline); !s) {
      exit_code = cli::report(s.error());
      return;
    }
    if (run.scenes.empty()) run.scenes = {default_scene()};
    run.gaze.size_given = size->count() > 0;
    exit_code = bench::run_bench(run, sweep_options(*sub));
  });
}

void add_bench_merge(CLI::App& bench_app, int& exit_code) {
  auto a = std::make_shared<bench::MergeOptions>();
  CLI::App* sub = bench_app.add_subcommand("merge", "Join the shards of a sweep (bench --shard K/N) into one run's bench.csv/json and charts");
  sub->add_option("--out,-o", a->out, "Output directory")->required();
  sub->add_option("shards", a->shards, "The shards' output directories, all N of them, in any order")->required();
  sub->add_flag("--no-png", a->no_png, "CSV and JSON only");
  sub->add_flag("--json", a->json, "Print the merged results as JSON");
  sub->callback([a, &exit_code] { exit_code = bench::run_merge(*a); });
}

}  // namespace foveal::cmd

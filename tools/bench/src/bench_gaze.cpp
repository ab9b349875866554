#include "foveal/bench/bench_gaze.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "foveal/bench/bench_flicker.hpp"
#include "foveal/bench/bench_jod.hpp"
#include "foveal/bench/bench_outputs.hpp"
#include "foveal/bench/bench_sweep.hpp"
#include "foveal/bench/gaze_timeline.hpp"
#include "foveal/bench/gaze_video.hpp"
#include "foveal/core/atomic_file.hpp"
#include "foveal/core/data_paths.hpp"
#include "foveal/core/gaze_log.hpp"
#include "foveal/core/json_text.hpp"
#include "foveal/image/metrics.hpp"
#include "foveal/render/compositor.hpp"
#include "foveal/render/egl_context.hpp"
#include "foveal/render/scene.hpp"
#include "foveal/runtime/cli.hpp"

namespace foveal::bench {

namespace {

using render::Method;

constexpr auto fmt = bench::csv_number;
constexpr auto jnum = bench::json_number;

/// Linear interpolation between order statistics (numpy's default), q in [0, 1].
double quantile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const std::size_t lo = static_cast<std::size_t>(std::floor(pos)), hi = std::min(lo + 1, v.size() - 1);
  if (!std::isfinite(v[lo]) || !std::isfinite(v[hi])) return v[lo];
  return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

/// A figure that may have no value (no frame after a saccade; no run without accumulation
/// to compare with): null in the JSON, an empty cell in the CSV.
nlohmann::json or_null(double v) { return std::isnan(v) ? nlohmann::json() : nlohmann::json(v); }

// Patch PSNRs above this count as this: an RMS error under one 8-bit level is not an
// error a viewer sees, and an identical patch (∞ dB) would make every other frame "worse".
constexpr double kPatchCeilingDb = 50.0;

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? NAN : s / static_cast<double>(v.size());
}

Result<DisplayModel> load_model(const std::string& spec) {
  if (spec.empty()) return DisplayModel::vive_pro_eye();
  return DisplayModel::load(display_model_path(spec));
}

struct LogInput {
  std::string path, name;
  bool head_recorded = false;
  GazeTimeline timeline;
  GazeTimeline video;  ///< --gaze-video's consecutive frames (none without)
};

/// One method × level's frames on one scene and log.
struct Series {
  std::vector<double> fpsnr, ssim, psnr, patch, error_deg;
  std::vector<double> jod;  ///< both eyes' (StereoJod::combined); empty with --no-jod
  std::size_t exceed = 0;
};

// One method at one level. The oracle is RMFR+EFR with its fovea on the true gaze at
// display time (perfect, zero-latency tracking): the per-frame bound of the patch error.
struct Point {
  Method method;
  double sigma;
  bool oracle = false;
  const char* gaze() const { return oracle ? "true" : render::follows_gaze(method) ? "filtered" : "none"; }
};

// gaze.csv's columns, in order: the keys of a summary row (docs/bench.md).
const std::vector<std::string> kSummaryColumns = {
    "scene", "log", "display", "method", "gaze", "sigma_d", "sigma_nd", "shaded_samples", "cost", "gpu_ms", "cpu_ms",
    "frames", "blink_frames", "fpsnr_mean", "fpsnr_p5", "fpsnr_min", "ssim_mean", "ssim_p5", "ssim_min", "psnr_mean",
    "patch_psnr_mean", "patch_psnr_p5", "patch_exceed_share", "fovea_error_deg_mean"};
// Appended to gaze.csv unless --no-jod, so that readers by position still find the rest.
const std::vector<std::string> kJodSummaryColumns = {"jod_mean", "jod_p5", "jod_min"};

std::vector<std::string> summary_columns(bool jod) {
  std::vector<std::string> c = kSummaryColumns;
  if (jod) c.insert(c.end(), kJodSummaryColumns.begin(), kJodSummaryColumns.end());
  return c;
}

/// One CSV line of `row`'s values in `columns` order; the header line for a null row.
std::string csv_line(const nlohmann::json& row, const std::vector<std::string>& columns) {
  std::string line;
  for (const std::string& c : columns) {
    if (&c != &columns.front()) line += ",";
    if (row.is_null()) line += c;
    else if (row.at(c).is_null()) continue;  // no value: an empty cell
    else if (row.at(c).is_string()) line += row.at(c).get<std::string>();
    else if (row.at(c).is_number_integer() || row.at(c).is_number_unsigned()) line += json_text(row.at(c));
    else line += fmt(row.at(c).get<double>());
  }
  return line + "\n";
}

/// A method × level's figures over the frames of one scene and log.
nlohmann::json summary_row(const Point& p, const Series& se, const render::PassTimes& t, double efr_ratio, double full_samples,
                           bool jod) {
  const std::size_t n = se.fpsnr.size();
  auto lowest = [n](const std::vector<double>& v) { return n ? *std::min_element(v.begin(), v.end()) : NAN; };
  nlohmann::json row = {{"method", render::method_name(p.method)}, {"gaze", p.gaze()}, {"sigma_d", p.sigma},
          {"sigma_nd", p.sigma * efr_ratio}, {"shaded_samples", t.shaded_samples},
          {"cost", static_cast<double>(t.shaded_samples) / full_samples}, {"gpu_ms", t.gpu_total}, {"cpu_ms", t.cpu},
          {"frames", n}, {"fpsnr_mean", jnum(mean(se.fpsnr))}, {"fpsnr_p5", jnum(quantile(se.fpsnr, 0.05))},
          {"fpsnr_min", jnum(lowest(se.fpsnr))}, {"ssim_mean", jnum(mean(se.ssim))}, {"ssim_p5", jnum(quantile(se.ssim, 0.05))},
          {"ssim_min", jnum(lowest(se.ssim))}, {"psnr_mean", jnum(mean(se.psnr))}, {"patch_psnr_mean", jnum(mean(se.patch))},
          {"patch_psnr_p5", jnum(quantile(se.patch, 0.05))},
          {"patch_exceed_share", jnum(n ? static_cast<double>(se.exceed) / static_cast<double>(n) : NAN)},
          {"fovea_error_deg_mean", jnum(mean(se.error_deg))}};
  if (jod) row.update({{"jod_mean", jnum(mean(se.jod))}, {"jod_p5", jnum(quantile(se.jod, 0.05))}, {"jod_min", jnum(lowest(se.jod))}});
  return row;
}

class GazeBench {
 public:
  GazeBench(const GazeBenchOptions& g, const GazeBenchSweep& s, render::Compositor& c, const DisplayModel& m,
            cli::Progress& p)
      : g_(g), s_(s), comp_(c), model_(m), progress_(p) {
    const EyeFrustum& f = model_.eye(Eye::left);
    ppd_ = comp_.eye_width() / (static_cast<double>(f.tan_right) - f.tan_left) * 3.14159265358979323846 / 180.0;
  }

  double ppd() const { return ppd_; }

  render::FrameParams params(Method m, double sigma, const GazeFrame& f, bool oracle = false, bool temporal = false) const {
    render::FrameParams p = render::efr_frame(m, Eye::right, sigma, m == Method::full ? sigma : sigma * g_.efr_ratio, s_.fx, s_.fy);
    const auto& fovea = oracle ? f.truth : f.fovea;
    for (std::size_t i = 0; i < 2; ++i) p.eyes[i].fovea_x = fovea[i].x, p.eyes[i].fovea_y = fovea[i].y, p.eyes[i].inset_deg = g_.inset_deg;
    if (f.head.valid) p.head = f.head.relative;
    p.pipeline = s_.pipeline;
    p.temporal = temporal;
    p.blend_at = s_.blend_at;
    return p;
  }

  /// The median frame of warm-up + timed renders (the bench's frame time).
  Result<render::PassTimes> time(const render::Scene& scene, const render::FrameParams& p) {
    std::vector<render::PassTimes> t;
    for (int i = 0; i < s_.warmup + s_.timed_frames; ++i) {
      auto r = comp_.render(scene, p);
      if (!r) return r.error();
      if (i >= s_.warmup) t.push_back(*r);
    }
    progress_.update(++done_);
    return render::median_pass_times(t);
  }

  Result<image::Image> render(const render::Scene& scene, const render::FrameParams& p) {
    auto r = comp_.render(scene, p);
    if (!r) return r.error();
    progress_.update(++done_);
    return comp_.read_image();
  }

  /// A video frame's FPSNR and fovea patch at the true gaze, and with `jod` its still JOD.
  Result<VideoFrameFigures> frame_figures(const image::Image& ref, const image::Image& img, const GazeFrame& f, StereoJodScorer* jod) const {
    image::MetricsOptions mo;
    mo.ppd = ppd_;
    mo.fovea = {f.truth[0].x, f.truth[0].y};
    mo.fovea_right = {f.truth[1].x, f.truth[1].y};
    auto q = image::compute_stereo_metrics(ref, img, mo);
    if (!q) return q.error();
    VideoFrameFigures out;
    out.fpsnr_db = q->combined.fpsnr_db;
    out.patch_psnr_db = kPatchCeilingDb;
    for (Eye e : kEyes) out.patch_psnr_db = std::min(out.patch_psnr_db, image::psnr(ref, img, patch(e, f.truth[static_cast<std::size_t>(e)])));
    if (jod) {
      auto j = jod->still(ref, img, std::array<double, 2>{f.truth[0].x, f.truth[0].y}, std::array<double, 2>{f.truth[1].x, f.truth[1].y});
      if (!j) return j.error();
      out.jod = *j;
    }
    return out;
  }

  /// The fovea patch of eye `e`: a square of patch_deg degrees around the true gaze.
  image::Rect patch(Eye e, glm::dvec2 truth) const {
    const int w = comp_.eye_width(), h = comp_.height();
    const int half = std::max(1, static_cast<int>(std::lround(g_.patch_deg / 2 * ppd_)));
    const int cx = static_cast<int>(truth.x * w), cy = static_cast<int>(truth.y * h);
    const int x0 = std::clamp(cx - half, 0, w - 1), x1 = std::clamp(cx + half, x0 + 1, w);
    const int y0 = std::clamp(cy - half, 0, h - 1), y1 = std::clamp(cy + half, y0 + 1, h);
    return {x0 + (e == Eye::right ? w : 0), y0, x1 - x0, y1 - y0};
  }

 private:
  const GazeBenchOptions& g_;
  const GazeBenchSweep& s_;
  render::Compositor& comp_;
  const DisplayModel& model_;
  cli::Progress& progress_;
  double ppd_ = 13.15;
  std::uint64_t done_ = 0;
};

}  // namespace

int run_gaze_bench(const GazeBenchOptions& g, const GazeBenchSweep& s) {
  auto fail = [](const Error& e) { return cli::report(e); };
  const auto started = std::chrono::steady_clock::now();
  auto shard = bench::parse_shard(s.shard.empty() ? "1/1" : s.shard);
  if (!shard) return fail(shard.error());
  auto model = load_model(g.display);
  if (!model) return fail(model.error());
  std::pair<int, int> size = s.size;
  if (!g.size_given) size = {model->output_width(), model->output_height()};
  if (g.video_frames < 0) return fail(bad_input("--gaze-video must be >= 0 (0: no video)"));
  if (g.video_frames > 0 && !s.jod) return fail(bad_input("--gaze-video scores the sequences with JOD: drop --no-jod"));

  GazeTimelineOptions to;
  to.fps = g.fps, to.latency_ms = g.latency_ms, to.start_s = g.start_s, to.frames = g.frames;
  to.pick = g.pick == "spread" ? GazeTimelineOptions::Pick::spread : GazeTimelineOptions::Pick::even;
  to.spread_max_deg = g.spread_max_deg;
  std::vector<LogInput> logs;
  for (const std::string& path : g.logs) {
    auto samples = read_gaze_log(path);
    if (!samples) return fail(samples.error());
    const bool has_pose = std::any_of(samples->begin(), samples->end(), [](const GazeSample& x) { return x.head.valid; });
    if (g.head == "recorded" && !has_pose)
      return fail(bad_input("--head recorded: " + path + " carries no head pose (a native log v2 with head columns has one)"));
    LogInput in{path, std::filesystem::path(path).stem().string(), g.head.empty() ? has_pose : g.head == "recorded", {}, {}};
    to.head_recorded = in.head_recorded;
    // The filter foveald runs without a profile (docs/filtering.md).
    auto tl = build_gaze_timeline(*samples, *model, FilterConfig{}, to);
    if (!tl) return fail(Error{tl.error().kind, path + ": " + tl.error().message});
    in.timeline = std::move(*tl);
    if (g.video_frames > 0) {
      // The same stream and latency model, its first N frames from --gaze-start in a row.
      GazeTimelineOptions vo = to;
      vo.pick = GazeTimelineOptions::Pick::consecutive;
      vo.frames = g.video_frames;
      auto v = build_gaze_timeline(*samples, *model, FilterConfig{}, vo);
      if (!v) return fail(Error{v.error().kind, path + ": --gaze-video: " + v.error().message});
      in.video = std::move(*v);
    }
    logs.push_back(std::move(in));
  }

  std::error_code ec;
  std::filesystem::create_directories(s.out, ec);
  if (ec) return fail(io_error(s.out + ": cannot create directory: " + ec.message()));
  auto ctx = gl::EglContext::create();
  if (!ctx) return fail(ctx.error());
  render::CompositorOptions co;
  co.width = size.first, co.height = size.second;
  co.model = *model;
  auto comp = render::Compositor::create(co);
  if (!comp) return fail(comp.error());
  std::optional<StereoJodScorer> jod;  // each eye alone at its true gaze, on the model rendered for
  if (s.jod) {
    auto j = StereoJodScorer::create(co.model, co.width, co.height, 2, s.light);
    if (!j) return fail(j.error());
    jod.emplace(std::move(*j));
  }
  const std::vector<std::string> columns = summary_columns(s.jod);

  // Level by level, the oracle first: each frame's patch bound comes from it.
  std::vector<Point> points;
  for (double sigma : s.sigmas) {
    points.push_back({Method::rmfr, sigma, true});
    for (Method m : s.methods) points.push_back({m, sigma});
  }
  // --gaze-video's runs per level: each point once per accumulation value that applies to it.
  std::size_t video_runs = 0;
  for (const Point& p : points) video_runs += temporal_values(s.temporal, p.method, s.pipeline).size();
  std::uint64_t total = s.scenes.size() * points.size();
  for (const LogInput& l : logs) {
    std::uint64_t renders = l.head_recorded ? 0 : 1;  // the full reference: per frame, or once with a static head
    for (const GazeFrame& f : l.timeline.frames) renders += f.blink ? 0 : points.size() + (l.head_recorded ? 1 : 0);
    if (!l.video.frames.empty()) renders += (l.head_recorded ? 0 : 1) + video_runs;  // + each run's timing
    for (const GazeFrame& f : l.video.frames) renders += f.blink ? 0 : video_runs + (l.head_recorded ? 1 : 0);
    total += s.scenes.size() * renders;
  }
  cli::Progress progress("bench --gaze", total / static_cast<std::uint64_t>(shard->n), !s.json);
  GazeBench bench(g, s, *comp, *model, progress);
  const double full_samples = static_cast<double>(co.width) * co.height;

  // The sweep's points (bench_sweep.hpp): scene × log × level, each level with its oracle
  // (every frame's patch bound) and every method. The frame loop visits a scene and log's
  // levels again and again, so a shard takes its points first and tags the rows with them.
  auto chomp = [](std::string line) { return line.substr(0, line.size() - 1); };
  bench::SweepRows rows(*shard);
  rows.table("gaze.csv", chomp(csv_line(nullptr, columns)));
  rows.table("gaze_frames.csv",
             "scene,log,frame,t_render_s,t_display_s,t_sample_s,true_l_x,true_l_y,true_r_x,true_r_y,method,gaze,sigma_d,fovea_l_x,"
             "fovea_l_y,fovea_r_x,fovea_r_y,error_l_deg,error_r_deg,fpsnr_db,ssim,psnr_db,patch_psnr_db,exceeds" +
                 std::string(jod ? ",jod_left,jod_right,jod" : "") + ",true_ecc_deg");
  std::vector<std::string> video_columns;  // gaze_video.csv's, in order
  if (g.video_frames > 0) {
    rows.table("gaze_video.csv", kGazeVideoColumns);
    rows.table("gaze_video_frames.csv", kGazeVideoFrameColumns);
    std::istringstream in(kGazeVideoColumns);
    for (std::string c; std::getline(in, c, ',');) video_columns.push_back(c);
  }
  const std::size_t per_level = 1 + s.methods.size();
  for (const std::string& spec : s.scenes) {
    // owned[log][level]: the point, where this shard runs it.
    std::vector<std::vector<std::optional<std::size_t>>> owned(logs.size(), std::vector<std::optional<std::size_t>>(s.sigmas.size()));
    std::vector<bool> level_owned(s.sigmas.size(), false);
    for (auto& log_points : owned)
      for (std::size_t v = 0; v < log_points.size(); ++v)
        if (std::size_t id = 0; rows.take(&id)) log_points[v] = id, level_owned[v] = true;
    if (std::none_of(level_owned.begin(), level_owned.end(), [](bool b) { return b; })) continue;
    auto scene = render::load_scene(spec);
    if (!scene) return fail(scene.error());
    for (const std::string& w : scene->warnings) cli::warn(w);
    const std::string scene_name = std::filesystem::path(spec).stem().string();
    // Frame time per point: the bench's median, at the first log's first frame.
    std::vector<render::PassTimes> times(points.size());
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (!level_owned[k / per_level]) continue;
      const Point& p = points[k];
      auto t = bench.time(*scene, bench.params(p.method, p.sigma, logs.front().timeline.frames.front(), p.oracle));
      if (!t) return fail(t.error());
      times[k] = *t;
    }
    for (std::size_t li = 0; li < logs.size(); ++li) {
      const LogInput& log = logs[li];
      const auto& mine = owned[li];
      if (std::none_of(mine.begin(), mine.end(), [](const auto& p) { return p.has_value(); })) continue;
      std::vector<Series> series(points.size());
      const TimeNs t0 = log.timeline.frames.front().t_render - static_cast<TimeNs>(std::llround(g.start_s * 1e9));
      auto secs = [&](TimeNs t) { return fmt(static_cast<double>(t - t0) / 1e9); };
      std::size_t blinks = 0;
      std::optional<image::Image> ref;  // a static head sees the same reference every frame
      for (const GazeFrame& f : log.timeline.frames) {
        if (f.blink) {
          ++blinks;
          continue;
        }
        if (!ref || f.head.valid) {
          auto r = bench.render(*scene, bench.params(Method::full, 1.0, f));
          if (!r) return fail(r.error());
          ref = std::move(*r);
        }
        image::MetricsOptions mo;
        mo.ppd = bench.ppd();
        mo.fovea = {f.truth[0].x, f.truth[0].y};
        mo.fovea_right = {f.truth[1].x, f.truth[1].y};
        const std::string frame_head = scene_name + "," + log.name + "," + std::to_string(f.index) + "," + secs(f.t_render) +
                                       "," + secs(f.t_display) + "," + secs(f.t_sample) + "," + fmt(f.truth[0].x) + "," +
                                       fmt(f.truth[0].y) + "," + fmt(f.truth[1].x) + "," + fmt(f.truth[1].y);
        double bound = -INFINITY;  // the oracle's patch PSNR minus the margin, at this level
        for (std::size_t k = 0; k < points.size(); ++k) {
          if (!mine[k / per_level]) continue;
          const Point& p = points[k];
          auto img = bench.render(*scene, bench.params(p.method, p.sigma, f, p.oracle));
          if (!img) return fail(img.error());
          auto q = image::compute_stereo_metrics(*ref, *img, mo);
          if (!q) return fail(q.error());
          std::array<glm::dvec2, 2> used{};
          std::array<double, 2> err{};
          double patch = INFINITY;
          for (Eye e : kEyes) {
            const std::size_t i = static_cast<std::size_t>(e);
            const render::EyePlan& plan = comp->plan(e);
            used[i] = plan.fovea;
            err[i] = render::eccentricity_deg(plan.frustum, plan.fovea, f.truth[i]);
            patch = std::min({patch, image::psnr(*ref, *img, bench.patch(e, f.truth[i])), kPatchCeilingDb});
          }
          std::string jod_cells;
          if (jod) {
            auto j = jod->still(*ref, *img, std::array<double, 2>{f.truth[0].x, f.truth[0].y}, std::array<double, 2>{f.truth[1].x, f.truth[1].y});
            if (!j) return fail(j.error());
            series[k].jod.push_back(j->combined);
            jod_cells = "," + fmt(j->left) + "," + fmt(j->right) + "," + fmt(j->combined);
          }
          if (p.oracle) bound = patch - g.patch_margin_db;
          const bool exceeds = patch < bound;
          Series& se = series[k];
          se.fpsnr.push_back(q->combined.fpsnr_db);
          se.ssim.push_back(q->combined.ssim);
          se.psnr.push_back(q->combined.psnr_db);
          se.patch.push_back(patch);
          se.error_deg.push_back(0.5 * (err[0] + err[1]));
          se.exceed += exceeds ? 1 : 0;
          rows.add_line("gaze_frames.csv",
                        frame_head + "," + render::method_name(p.method) + "," + p.gaze() + "," + fmt(p.sigma) + "," + fmt(used[0].x) +
                            "," + fmt(used[0].y) + "," + fmt(used[1].x) + "," + fmt(used[1].y) + "," + fmt(err[0]) + "," +
                            fmt(err[1]) + "," + fmt(q->combined.fpsnr_db) + "," + fmt(q->combined.ssim) + "," +
                            fmt(q->combined.psnr_db) + "," + fmt(patch) + "," + (exceeds ? "1" : "0") + jod_cells + "," +
                            fmt(f.truth_ecc_deg),
                        *mine[k / per_level]);
        }
      }
      for (std::size_t k = 0; k < points.size(); ++k) {
        if (!mine[k / per_level]) continue;
        nlohmann::json row = summary_row(points[k], series[k], times[k], g.efr_ratio, full_samples, s.jod);
        row.update({{"scene", scene_name}, {"log", log.name}, {"display", model->name}, {"blink_frames", blinks}});
        rows.add_line("gaze.csv", chomp(csv_line(row, columns)), *mine[k / per_level]);
        rows.add_item("rows", std::move(row), *mine[k / per_level]);
      }
      if (log.video.frames.empty()) continue;
      // --gaze-video: the sequence's references once per scene and log (kept whole, W·H·4
      // bytes a frame), then each point's frames as one video against them.
      const std::vector<GazeFrame>& vf = log.video.frames;
      std::vector<image::Image> vrefs;
      std::vector<std::size_t> ref_of(vf.size(), 0);
      for (std::size_t k = 0; k < vf.size(); ++k) {
        if (vf[k].blink) continue;
        if (vrefs.empty() || vf[k].head.valid) {
          auto r = bench.render(*scene, bench.params(Method::full, 1.0, vf[k]));
          if (!r) return fail(r.error());
          vrefs.push_back(std::move(*r));
        }
        ref_of[k] = vrefs.size() - 1;
      }
      const double head_speed = mean_head_speed_deg_s(vf, g.fps);
      const SaccadeWindows saccades = find_saccades(vf, *model, g.fps);
      auto reference = [&](std::size_t k) -> Result<image::Image> { return vrefs.at(ref_of[k]); };
      for (std::size_t k = 0; k < points.size(); ++k) {
        if (!mine[k / per_level]) continue;
        const Point& p = points[k];
        std::vector<VideoFrameFigures> off;  // this point's frames without accumulation, for the on run
        for (bool temporal : temporal_values(s.temporal, p.method, s.pipeline)) {
          comp->reset_history();  // the timing's frames are no part of the video
          auto t = bench.time(*scene, bench.params(p.method, p.sigma, vf.front(), p.oracle, temporal));
          if (!t) return fail(t.error());
          comp->reset_history();
          std::vector<VideoFrameFigures> figures(vf.size());
          auto test = [&](std::size_t i) { return bench.render(*scene, bench.params(p.method, p.sigma, vf[i], p.oracle, temporal)); };
          auto check = [&](std::size_t i, const image::Image& r, const image::Image& img) -> Status {
            auto fig = bench.frame_figures(r, img, vf[i], saccades.post[i] ? &*jod : nullptr);
            if (!fig) return fig.error();
            figures[i] = *fig;
            return {};
          };
          auto v = score_gaze_video(*jod, g.fps, vf, reference, test, check);
          if (!v) return fail(Error{v.error().kind, log.path + ": " + v.error().message});
          const PostSaccade after = post_saccade(saccades, figures, temporal ? &off : nullptr);
          const char* on_off = temporal ? "on" : "off";
          nlohmann::json row = {{"scene", scene_name}, {"log", log.name}, {"display", model->name}, {"method", render::method_name(p.method)},
                                {"gaze", p.gaze()}, {"sigma_d", p.sigma}, {"sigma_nd", p.sigma * g.efr_ratio}, {"frames", v->frames},
                                {"blink_frames", v->blink_frames}, {"fps", g.fps}, {"head_speed_deg_s", head_speed},
                                {"jod_left", v->jod.left}, {"jod_right", v->jod.right}, {"jod", v->jod.combined}, {"temporal", on_off},
                                {"shaded_samples", t->shaded_samples}, {"cost", static_cast<double>(t->shaded_samples) / full_samples},
                                {"gpu_ms", t->gpu_total}, {"cpu_ms", t->cpu}, {"saccades", saccades.onsets},
                                {"post_saccade_frames", after.frames}, {"post_saccade_fpsnr_mean", or_null(after.fpsnr_mean)},
                                {"post_saccade_jod_mean", or_null(after.jod_mean)}, {"post_saccade_fpsnr_worst_vs_off", or_null(after.fpsnr_worst_vs_off)},
                                {"post_saccade_jod_worst_vs_off", or_null(after.jod_worst_vs_off)}};
          rows.add_line("gaze_video.csv", chomp(csv_line(row, video_columns)), *mine[k / per_level]);
          rows.add_item("video", std::move(row), *mine[k / per_level]);
          for (std::size_t i = 0; i < vf.size(); ++i) {
            if (vf[i].blink) continue;
            const VideoFrameFigures& fg = figures[i];
            const std::string jod_cells = fg.jod ? fmt(fg.jod->left) + "," + fmt(fg.jod->right) + "," + fmt(fg.jod->combined) : ",,";
            rows.add_line("gaze_video_frames.csv",
                          scene_name + "," + log.name + "," + render::method_name(p.method) + "," + p.gaze() + "," + fmt(p.sigma) + "," +
                              on_off + "," + std::to_string(vf[i].index) + "," + secs(vf[i].t_display) + "," + fmt(saccades.step_deg[i]) +
                              "," + (saccades.post[i] ? "1" : "0") + "," + fmt(fg.fpsnr_db) + "," + fmt(fg.patch_psnr_db) + "," + jod_cells,
                          *mine[k / per_level]);
          }
          if (!temporal) off = std::move(figures);
        }
      }
    }
  }
  progress.finish();
  if (jod && !s.json) print_jod_cost(*jod, "bench --gaze", started);

  rusage ru{};
  ::getrusage(RUSAGE_SELF, &ru);
  nlohmann::json log_info = nlohmann::json::array();
  for (const LogInput& l : logs)
    log_info.push_back({{"path", l.path}, {"name", l.name}, {"head", l.head_recorded ? "recorded" : "static"},
                        {"stream_frames", l.timeline.stream_frames}, {"stride", l.timeline.stride}, {"pick", g.pick},
                        {"scored_frames", l.timeline.frames.size()}, {"video_frames", l.video.frames.size()}});
  nlohmann::json summary = {
      {"renderer", comp->renderer()}, {"display", model->name}, {"size", {co.width, co.height}},
      {"ppd", bench.ppd()}, {"fps", g.fps}, {"latency_ms", logs.front().timeline.latency_ms},
      {"start_s", g.start_s}, {"efr_ratio", g.efr_ratio}, {"dominant", "right"}, {"fx", s.fx}, {"fy", s.fy}, {"inset_deg", g.inset_deg},
      {"patch_deg", g.patch_deg}, {"patch_margin_db", g.patch_margin_db}, {"filter", "FilterConfig defaults (foveald without a profile)"},
      {"timed_frames", s.timed_frames}, {"logs", log_info}, {"video_frames", g.video_frames},
      {"pipeline", render::pipeline_name(s.pipeline)}, {"temporal", s.temporal.back() ? s.temporal.front() ? "on" : "off,on" : "off"},
      {"blend_at", render::blend_at_name(s.blend_at)},
      {"temporal_history_mb", static_cast<double>(comp->memory().temporal) / 1e6},
      {"wall_s", std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count()},
      {"peak_rss_mb", static_cast<double>(ru.ru_maxrss) / 1024.0}};
  if (jod) summary["jod"] = jod_settings(*jod);
  // --shard given (1/1 too): a part for `bench merge`.
  if (!s.shard.empty()) return bench::write_shard(s.out, rows, summary, s.sweep, "gaze", s.json);
  return bench::write_outputs(s.out, rows, summary, "gaze", !s.no_png, s.json);
}

}  // namespace foveal::bench

#include "foveal/bench/bench_run.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "foveal/bench/bench_flicker.hpp"
#include "foveal/bench/bench_jod.hpp"
#include "foveal/bench/bench_outputs.hpp"
#include "foveal/bench/bench_sweep.hpp"
#include "foveal/image/auto_f.hpp"
#include "foveal/image/metrics.hpp"
#include "foveal/render/egl_context.hpp"
#include "foveal/render/scene.hpp"
#include "foveal/runtime/args.hpp"
#include "foveal/runtime/cli.hpp"

namespace foveal::bench {

namespace {

using render::Method;

constexpr auto num = bench::csv_number;

Result<std::vector<double>> parse_range(const std::string& s, const std::string& what) {
  std::vector<double> out;
  if (s.find(':') != std::string::npos) {
    double a = 0, b = 0, step = 0;
    char c1 = 0, c2 = 0;
    std::istringstream in(s);
    if (!(in >> a >> c1 >> b >> c2 >> step) || c1 != ':' || c2 != ':' || !(step > 0) || b < a || !std::isfinite(a) || !std::isfinite(b))
      return bad_input(what + ": expected FROM:TO:STEP or a comma list, got '" + s + "'");
    for (int i = 0; a + i * step <= b + 1e-9 && i < 1000; ++i) out.push_back(std::round((a + i * step) * 1e6) / 1e6);
  } else {
    std::istringstream in(s);
    std::string item;
    while (std::getline(in, item, ',')) {
      char* end = nullptr;
      const double v = std::strtod(item.c_str(), &end);
      if (item.empty() || *end || !std::isfinite(v)) return bad_input(what + ": '" + item + "' is not a number");
      out.push_back(v);
    }
  }
  if (out.empty()) return bad_input(what + ": no values");
  return out;
}

struct Measured {
  render::PassTimes median;  ///< its shaded_samples: the samples every frame shades
  image::Image image;
};

class Bench {
 public:
  Bench(const BenchOptions& a, render::Compositor& c, cli::Progress& p) : a_(a), comp_(c), progress_(p) {}

  void tick() { progress_.update(++done_); }

  Result<Measured> measure(const render::Scene& s, const render::FrameParams& f, int frames) {
    std::vector<render::PassTimes> t;
    for (int i = 0; i < a_.warmup + frames; ++i) {
      render::FrameParams p = f;
      p.pipeline = a_.pipeline;
      p.blend_at = a_.blend_at;
      auto r = comp_.render(s, p);
      if (!r) return r.error();
      if (i >= a_.warmup) t.push_back(*r);
    }
    progress_.update(++done_);
    Measured m;
    m.median = render::median_pass_times(t);
    m.image = comp_.read_image();
    return m;
  }

 private:
  const BenchOptions& a_;
  render::Compositor& comp_;
  cli::Progress& progress_;
  std::uint64_t done_ = 0;
};

render::FrameParams uniform_frame(Method m, double sigma, double fx, double fy, std::pair<double, double> fovea) {
  render::FrameParams p = render::efr_frame(m, Eye::right, sigma, sigma, fx, fy);
  for (auto& e : p.eyes) e.fovea_x = fovea.first, e.fovea_y = fovea.second;
  return p;
}

// The JOD cells appended to a row of the experiments' tables (both eyes at `fovea`, as
// their FPSNR), or nothing without JOD.
Result<std::string> jod_cells(StereoJodScorer* jod, const image::Image& ref, const image::Image& test, std::pair<double, double> fovea) {
  if (!jod) return std::string();
  const EyeFovea f = std::array<double, 2>{fovea.first, fovea.second};
  auto j = jod->still(ref, test, f, f);
  if (!j) return j.error();
  return "," + num(j->left) + "," + num(j->right) + "," + num(j->combined);
}

image::MetricsOptions metric_options(const render::Compositor& c, std::pair<double, double> fovea) {
  image::MetricsOptions o;
  o.ppd = c.plan(Eye::left).pixels_per_degree();
  o.fovea = {fovea.first, fovea.second};
  o.fovea_right = o.fovea;
  return o;
}

}  // namespace

int run_bench(const BenchOptions& a, const std::string& sweep) {
  const auto started = std::chrono::steady_clock::now();
  auto fail = [](const Error& e) { return cli::report(e); };
  if (a.out.empty()) return fail(bad_input("--out is required"));
  std::vector<Method> methods;
  {
    std::istringstream in(a.methods);
    std::string m;
    while (std::getline(in, m, ',')) {
      auto parsed = render::parse_method(m);
      if (!parsed) return fail(parsed.error());
      if (*parsed != Method::full) methods.push_back(*parsed);
    }
  }
  auto sigmas = parse_range(a.sigmas, "--sigmas");
  if (!sigmas) return fail(sigmas.error());
  for (double s : *sigmas)
    if (s < 1) return fail(bad_input("--sigmas: every level must be >= 1"));
  auto fovea = cli::parse_point(a.fovea, "--fovea");
  if (!fovea) return fail(fovea.error());
  if (fovea->first < 0 || fovea->first > 1 || fovea->second < 0 || fovea->second > 1)
    return fail(bad_input("--fovea: X and Y must lie in [0,1]"));
  auto size = cli::parse_size(a.size, "--size");
  if (!size) return fail(size.error());
  if (size->first % 2) return fail(bad_input("--size: the width must be even"));
  if (a.frames < 1) return fail(bad_input("--frames must be >= 1"));
  if (Status s = a.light.validate(); !s)
    return fail(bad_input("--peak " + num(a.light.peak_cd_m2) + " --black " + num(a.light.black_cd_m2) +
                          ": the panel's luminance for JOD must be finite with 0 < black < peak (cd/m2)"));
  auto grid = parse_range(a.grid_values, "--grid-values");
  if (!grid) return fail(grid.error());
  auto shard = bench::parse_shard(a.shard.empty() ? "1/1" : a.shard);
  if (!shard) return fail(shard.error());
  auto temporal = parse_temporal_list(a.temporal);
  if (!temporal) return fail(temporal.error());
  if (temporal->back() && !a.flicker && a.gaze.video_frames == 0)
    return fail(bad_input("--temporal on: temporal accumulation needs a sequence of frames: add --flicker, or --gaze with --gaze-video"));
  // Charts come after the sweep and a failed chart step writes nothing: find a missing
  // matplotlib before the work, not after it.
  if (!a.no_png && a.shard.empty())
    if (Status s = bench::check_charts_can_run(); !s) return fail(s.error());
  const std::vector<std::string>& scenes = a.scenes;
  FlickerOptions fo;
  if (a.flicker) {
    auto cameras = parse_camera_paths(a.camera_paths);
    if (!cameras) return fail(cameras.error());
    auto gazes = parse_flicker_gazes(a.flicker_gaze);
    if (!gazes) return fail(gazes.error());
    auto pipelines = parse_flicker_pipelines(a.flicker_pipelines, a.pipeline);
    if (!pipelines) return fail(pipelines.error());
    if (a.flicker_sigma_nd && !(*a.flicker_sigma_nd >= 1 && std::isfinite(*a.flicker_sigma_nd)))
      return fail(bad_input("--flicker-sigma-nd: the level must be a number >= 1, got " + num(*a.flicker_sigma_nd)));
    if (a.camera_pivot && !(*a.camera_pivot > 0 && std::isfinite(*a.camera_pivot)))
      return fail(bad_input("--camera-pivot: expected a distance in metres > 0, got " + num(*a.camera_pivot)));
    fo = {.log = a.flicker_log, .frames = a.flicker_frames, .sigma = a.grid_sigma, .fx = a.fx, .fy = a.fy, .sigma_nd = a.flicker_sigma_nd.value_or(0),
          .fovea = *fovea, .cameras = *cameras, .pivot_m = a.camera_pivot.value_or(0), .fill = a.camera_fill, .gazes = *gazes, .pipelines = *pipelines,
          .own_reference = a.flicker_reference == "own", .temporal = *temporal, .blend_at = a.blend_at};
  }
  if (!a.gaze.logs.empty()) {
    if (a.f_grid || a.rotation || a.stability || a.flicker)
      return fail(bad_input("--gaze runs on its own: drop --f-grid, --rotation, --stability and --flicker"));
    return run_gaze_bench(a.gaze, {scenes, methods, *sigmas, *size, a.out, a.frames, a.warmup, a.fx, a.fy, a.no_png, a.json, a.shard, sweep,
                                   !a.no_jod, a.light, a.pipeline, *temporal, a.blend_at});
  }

  std::error_code ec;
  std::filesystem::create_directories(a.out, ec);
  if (ec) return fail(io_error(a.out + ": cannot create directory: " + ec.message()));
  auto ctx = gl::EglContext::create();
  if (!ctx) return fail(ctx.error());
  render::CompositorOptions co;
  co.width = size->first;
  co.height = size->second;
  auto comp = render::Compositor::create(co);
  if (!comp) return fail(comp.error());
  std::optional<StereoJodScorer> jod;  // each eye alone at the fovea, on the display model rendered for
  if (!a.no_jod) {
    auto j = StereoJodScorer::create(co.model, co.width, co.height, 2, a.light);
    if (!j) return fail(j.error());
    jod.emplace(std::move(*j));
  }

  const std::uint64_t per_scene = 1 + methods.size() * sigmas->size() + (a.f_grid ? grid->size() * grid->size() + 1 : 0);
  const std::uint64_t total = per_scene * scenes.size() + (a.rotation ? 19 * (1 + methods.size()) : 0) +
                              (a.stability ? 1 + 22 * methods.size() : 0) + (a.flicker ? flicker_points(fo, methods) * scenes.size() : 0);
  cli::Progress progress("bench", total / static_cast<std::uint64_t>(shard->n), !a.json);
  Bench bench(a, *comp, progress);

  // Each point of the grid (scene × method × level, f-grid point, angle × method, ...)
  // starts with rows.take(): a shard runs its points only, and renders a reference
  // only where it runs a point that needs it.
  bench::SweepRows rows(*shard);
  rows.table("bench.csv", "scene,method,sigma,shaded_samples,cost,gpu_ms,cpu_ms,shadow_ms,gbuffer_ms,mapping_ms,lighting_ms,inverse_ms,psnr_db,ssim,fpsnr_db,"
                             "blend_ms" + std::string(jod ? ",jod_left,jod_right,jod" : ""));
  // The experiments' JOD columns come last, so that readers by position find the rest.
  const std::string jod_columns = jod ? ",jod_left,jod_right,jod" : "";
  if (a.f_grid) rows.table("fgrid.csv", "scene,sigma,fx,fy,fpsnr_db,psnr_db,ssim" + jod_columns);
  if (a.rotation) rows.table("rotation.csv", "angle_deg,method,sigma,fpsnr_db,psnr_db,ssim" + jod_columns);
  if (a.stability) rows.table("stability.csv", "scene,path,t,fovea_x,fovea_y,method,sigma,patch_psnr_db,fpsnr_db" + jod_columns);
  StereoJodScorer* const jod_scorer = jod ? &*jod : nullptr;
  if (a.flicker) rows.table("flicker.csv", std::string(kFlickerColumns) + (jod ? kFlickerJodColumns : ""));
  const double full_samples = static_cast<double>(co.width) * co.height;
  for (std::size_t scene_index = 0; scene_index < scenes.size(); ++scene_index) {
    const std::string& spec = scenes[scene_index];
    const std::string name = std::filesystem::path(spec).stem().string();
    std::optional<render::Scene> scene;
    std::optional<Measured> full;
    image::MetricsOptions mo;  // the eye's pixels per degree are known once a frame is rendered
    auto reference = [&]() -> Status {
      if (full) return {};
      auto s = render::load_scene(spec);
      if (!s) return s.error();
      for (const std::string& w : s->warnings) cli::warn(w);
      scene = std::move(*s);
      auto f = bench.measure(*scene, uniform_frame(Method::full, 1, a.fx, a.fy, *fovea), a.frames);
      if (!f) return f.error();
      full = std::move(*f);
      mo = metric_options(*comp, *fovea);
      return {};
    };
    auto add_row = [&](Method m, double sigma, const Measured& r) -> Status {
      auto q = image::compute_stereo_metrics(full->image, r.image, mo);
      if (!q) return q.error();
      const auto& c = q->combined;
      const render::PassTimes& t = r.median;
      std::optional<StereoJod> j;
      const double jod_ms_before = jod ? jod->total_ms() : 0;
      if (jod) {
        const EyeFovea f = std::array<double, 2>{fovea->first, fovea->second};
        auto s = jod->still(full->image, r.image, f, f);
        if (!s) return s.error();
        j = *s;
      }
      rows.add_line("bench.csv", name + "," + render::method_name(m) + "," + num(sigma) + "," + std::to_string(r.median.shaded_samples) + "," +
                                     num(static_cast<double>(r.median.shaded_samples) / full_samples) + "," + num(t.gpu_total) + "," +
                                     num(t.cpu) + "," + num(t.shadow) + "," + num(t.gbuffer) + "," + num(t.mapping) + "," +
                                     num(t.lighting) + "," + num(t.inverse) + "," + num(c.psnr_db) + "," + num(c.ssim) + "," + num(c.fpsnr_db) +
                                     "," + num(t.blend) +
                                     (j ? "," + num(j->left) + "," + num(j->right) + "," + num(j->combined) : ""));
      nlohmann::json item = {{"scene", name}, {"method", render::method_name(m)}, {"sigma", sigma}, {"shaded_samples", r.median.shaded_samples},
                             {"gpu_ms", t.gpu_total}, {"cpu_ms", t.cpu},
                             {"passes_ms", {{"shadow", t.shadow}, {"gbuffer", t.gbuffer}, {"mapping", t.mapping},
                                            {"lighting", t.lighting}, {"inverse", t.inverse}, {"blend", t.blend}}},
                             {"blend_samples", t.blend_samples}, {"blend_layers", t.blend_layers}, {"blend_dropped", t.blend_dropped},
                             {"psnr_db", bench::json_number(c.psnr_db)}, {"ssim", c.ssim}, {"fpsnr_db", bench::json_number(c.fpsnr_db)}};
      if (j) {
        item["jod_left"] = j->left, item["jod_right"] = j->right, item["jod"] = j->combined;
        item["jod_ms"] = jod->total_ms() - jod_ms_before;
      }
      rows.add_item("rows", std::move(item));
      return {};
    };
    if (rows.take()) {
      if (Status s = reference(); !s) return fail(s.error());
      if (Status s = add_row(Method::full, 1.0, *full); !s) return fail(s.error());
    }
    for (Method m : methods)
      for (double sigma : *sigmas) {
        if (!rows.take()) continue;
        if (Status s = reference(); !s) return fail(s.error());
        auto r = bench.measure(*scene, uniform_frame(m, sigma, a.fx, a.fy, *fovea), a.frames);
        if (!r) return fail(r.error());
        if (Status s = add_row(m, sigma, *r); !s) return fail(s.error());
      }
    if (a.f_grid) {
      // The seed's Figure 6: RMFR's FPSNR over f_x × f_y at one level, and where the
      // automatic estimate lands (against the grid's best: bench_outputs.cpp).
      for (double fx : *grid)
        for (double fy : *grid) {
          if (!rows.take()) continue;
          if (Status s = reference(); !s) return fail(s.error());
          auto r = bench.measure(*scene, uniform_frame(Method::rmfr, a.grid_sigma, fx, fy, *fovea), 1);
          if (!r) return fail(r.error());
          // The grid search pays a render and a metric per point.
          const auto t0 = std::chrono::steady_clock::now();
          auto q = image::compute_stereo_metrics(full->image, r->image, mo);
          if (!q) return fail(q.error());
          const double ms = r->median.cpu + std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
          auto j = jod_cells(jod_scorer, full->image, r->image, *fovea);  // after the timing: the f search does not pay for it
          if (!j) return fail(j.error());
          rows.add_line("fgrid.csv", name + "," + num(a.grid_sigma) + "," + num(fx) + "," + num(fy) + "," + num(q->combined.fpsnr_db) +
                                         "," + num(q->combined.psnr_db) + "," + num(q->combined.ssim) + *j);
          rows.add_item("fgrid_points", {{"scene_index", scene_index}, {"fx", fx}, {"fy", fy}, {"fpsnr_db", bench::json_number(q->combined.fpsnr_db)}, {"ms", ms}});
        }
      if (rows.take()) {
        if (Status s = reference(); !s) return fail(s.error());
        auto est = image::estimate_rmfr_f(full->image, a.grid_sigma, mo);
        if (!est) return fail(est.error());
        auto r = bench.measure(*scene, uniform_frame(Method::rmfr, a.grid_sigma, est->fx, est->fy, *fovea), 1);
        if (!r) return fail(r.error());
        auto q = image::compute_stereo_metrics(full->image, r->image, mo);
        if (!q) return fail(q.error());
        rows.add_item("auto_f", {{"scene_index", scene_index}, {"scene", name}, {"sigma", a.grid_sigma}, {"auto_fx", est->fx},
                                 {"auto_fy", est->fy}, {"auto_fpsnr_db", bench::json_number(q->combined.fpsnr_db)}, {"auto_ms", est->ms},
                                 {"auto_evaluations", est->evaluations}});
      }
    }
  }

  if (a.rotation) {
    // The seed's Figure 12: vertical stripes rotated 0-180°, one level for every method.
    const double sigma = a.grid_sigma;
    for (int angle = 0; angle <= 180; angle += 10) {
      std::optional<render::Scene> scene;
      std::optional<Measured> full;
      for (Method m : methods) {
        if (!rows.take()) continue;
        if (!full) {
          auto s = render::load_scene("pattern:stripes-v@" + std::to_string(angle));
          if (!s) return fail(s.error());
          scene = std::move(*s);
          auto f = bench.measure(*scene, uniform_frame(Method::full, 1, a.fx, a.fy, *fovea), 1);
          if (!f) return fail(f.error());
          full = std::move(*f);
        }
        auto r = bench.measure(*scene, uniform_frame(m, sigma, a.fx, a.fy, *fovea), 1);
        if (!r) return fail(r.error());
        auto q = image::compute_stereo_metrics(full->image, r->image, metric_options(*comp, *fovea));
        if (!q) return fail(q.error());
        auto j = jod_cells(jod_scorer, full->image, r->image, *fovea);
        if (!j) return fail(j.error());
        rows.add_line("rotation.csv", std::to_string(angle) + "," + render::method_name(m) + "," + num(sigma) + "," +
                                          num(q->combined.fpsnr_db) + "," + num(q->combined.psnr_db) + "," + num(q->combined.ssim) + *j);
      }
    }
  }
  if (a.stability) {
    // Where methods break: the fovea walks from the centre to a corner and from the
    // centre to the bottom border; the 64-pixel patch around it and the whole frame.
    auto scene = render::load_scene("pattern:checker");
    if (!scene) return fail(scene.error());
    std::optional<Measured> full;
    const int eye_w = co.width / 2, eye_h = co.height;
    for (const char* path : {"diagonal", "vertical"})
      for (int i = 0; i <= 10; ++i) {
        const double t = i / 10.0;
        const std::pair<double, double> fv = std::string(path) == "diagonal" ? std::make_pair(0.5 - 0.5 * t, 0.5 - 0.5 * t)
                                                                             : std::make_pair(0.5, 0.5 + 0.5 * t);
        const int cx = static_cast<int>(fv.first * eye_w), cy = static_cast<int>(fv.second * eye_h);
        const image::Rect patch{std::clamp(cx - 32, 0, eye_w - 64), std::clamp(cy - 32, 0, eye_h - 64), 64, 64};
        for (Method m : methods) {
          if (!rows.take()) continue;
          if (!full) {
            auto f = bench.measure(*scene, uniform_frame(Method::full, 1, a.fx, a.fy, {0.5, 0.5}), 1);
            if (!f) return fail(f.error());
            full = std::move(*f);
          }
          auto r = bench.measure(*scene, uniform_frame(m, a.grid_sigma, a.fx, a.fy, fv), 1);
          if (!r) return fail(r.error());
          auto q = image::compute_stereo_metrics(full->image, r->image, metric_options(*comp, fv));
          if (!q) return fail(q.error());
          auto j = jod_cells(jod_scorer, full->image, r->image, fv);  // the eyes look where the fovea is, as FPSNR's weights
          if (!j) return fail(j.error());
          rows.add_line("stability.csv", std::string("pattern:checker,") + path + "," + num(t) + "," + num(fv.first) + "," + num(fv.second) +
                                             "," + render::method_name(m) + "," + num(a.grid_sigma) + "," +
                                             num(image::psnr(full->image, r->image, patch)) + "," + num(q->combined.fpsnr_db) + *j);
        }
      }
  }
  if (a.flicker)
    for (const std::string& spec : scenes)
      if (Status s = run_flicker(fo, *comp, methods, spec, rows, [&] { bench.tick(); }, jod_scorer); !s) return fail(s.error());
  progress.finish();
  if (jod && !a.json) print_jod_cost(*jod, "bench", started);

  rusage ru{};
  ::getrusage(RUSAGE_SELF, &ru);
  // What the charts' footer prints (tools/charts/run_settings.py): how each point was rendered and timed.
  nlohmann::json summary = {{"renderer", comp->renderer()}, {"size", {co.width, co.height}}, {"frames", a.frames},
                            {"warmup", a.warmup}, {"pipeline", render::pipeline_name(a.pipeline)},
                            {"blend_at", render::blend_at_name(a.blend_at)}, {"display", co.model.name},
                            {"fovea", {fovea->first, fovea->second}}, {"peak_rss_mb", static_cast<double>(ru.ru_maxrss) / 1024.0}};
  if (jod) summary["jod"] = jod_settings(*jod);
  // --shard given (1/1 too): a part for `bench merge`.
  if (!a.shard.empty()) return bench::write_shard(a.out, rows, summary, sweep, "bench", a.json);
  return bench::write_outputs(a.out, rows, summary, "bench", !a.no_png, a.json);
}

}  // namespace foveal::bench

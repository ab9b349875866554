// foveal render: one frame of a scene through the compositor (full or RMFR + EFR),
// saved as PNG, with per-pass timings (median of --frames timed frames after warm-up).
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "foveal/render/pipeline_comparison.hpp"

#include "commands.hpp"
#include "foveal/core/atomic_file.hpp"
#include "foveal/image/auto_f.hpp"
#include "foveal/render/egl_context.hpp"
#include "foveal/render/scene.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/evaluation/memory_bound.hpp"
#include "render/render_args.hpp"

namespace foveal::cmd {

namespace {

struct Args {
  RenderArgs render;
  std::string out;
  int frames = 5, warmup = 2;
  bool json = false;
  bool compare_pipelines = false;
  bool fill_view = false;
};

// Both pipelines' full and foveated frames, per pass, with the speedups against the
// faster full pipeline and the Amdahl limit (docs/rmfr.md, "Pipelines").
nlohmann::json pipelines_json(const render::PipelineComparison& c) {
  auto passes = [](const render::PassTimes& t) {
    const auto n = render::pass_names(t.pipeline);
    return nlohmann::json{{"shadow", t.shadow}, {n[0], t.gbuffer}, {n[1], t.mapping}, {"lighting", t.lighting},
                          {"inverse", t.inverse}, {"blend", t.blend}, {"gpu_total", t.gpu_total}, {"cpu_frame", t.cpu}};
  };
  nlohmann::json j = {{"best_full_gpu_ms", c.best_full_gpu()}};
  for (render::Pipeline p : render::all_pipelines()) {
    const std::size_t i = static_cast<std::size_t>(p);
    j[render::pipeline_name(p)] = {{"full_ms", passes(c.full[i])},
                                   {"foveated_ms", passes(c.foveated[i])},
                                   {"speedup", c.speedup(p)},
                                   {"fullres_share", c.fullres_share(p)},
                                   {"amdahl_limit", c.amdahl_limit(p)}};
  }
  return j;
}

// The head pose the frame used and where it (and each eye's fovea) came from.
nlohmann::json head_json(const RenderSetup& s) {
  const Pose& p = s.frame.head;
  const glm::quat q = p.orientation;
  nlohmann::json j = {{"source", s.head.kind},
                      {"position_m", {p.position_m.x, p.position_m.y, p.position_m.z}},
                      {"orientation_wxyz", {q.w, q.x, q.y, q.z}},
                      {"fovea_source", {{"left", s.head.fovea[0]}, {"right", s.head.fovea[1]}}}};
  if (s.head.kind == "log") j.update({{"log", s.head.log}, {"at_s", s.head.at_s}, {"sample_s", s.head.sample_s}});
  return j;
}

double mb(std::size_t bytes) { return static_cast<double>(bytes) / (1024.0 * 1024.0); }

// The frame's memory from its size alone, before a context or a target exists: with a
// software GL (llvmpipe) the render targets live in this process, and the frame is read
// back and encoded as PNG here. Peak RSS measured on llvmpipe from 1024x512 to 8192x4096:
// 30 bytes a pixel (either pipeline, full or RMFR), 45 with --compare-pipelines and
// --f auto (both pipelines' targets, the frame on the CPU), over ~300 MB (Dungeon's
// textures, the libraries).
constexpr std::uint64_t kRenderBytesPerPixel = 32, kRenderExtraBytesPerPixel = 14, kRenderBaseBytes = 300'000'000;

int run(const Args& a) {
  auto setup = resolve(a.render);
  if (!setup) return cli::report(setup.error());
  if (a.frames < 1) return cli::report(bad_input("--frames must be >= 1"));
  {
    const std::uint64_t w = static_cast<std::uint64_t>(setup->compositor.width), h = static_cast<std::uint64_t>(setup->compositor.height);
    const std::uint64_t per_px = kRenderBytesPerPixel + (a.compare_pipelines || setup->auto_f ? kRenderExtraBytesPerPixel : 0);
    if (Status s = evaluation::check_memory(per_px * w * h + kRenderBaseBytes, "a " + std::to_string(w) + "x" + std::to_string(h) + " frame"); !s)
      return cli::report(bad_input("render --size: " + s.error().message));
  }
  if (Status s = check_output_is_not_an_input(a.out, {setup->scene, a.render.display}); !s) return cli::report(s.error());
  auto ctx = gl::EglContext::create();
  if (!ctx) return cli::report(ctx.error());
  auto scene = render::load_scene(setup->scene, setup->scene_options);
  if (!scene) return cli::report(scene.error());
  for (const std::string& w : scene->warnings) cli::warn(w);
  if (a.fill_view) render::fill_view(*scene);
  auto comp = render::Compositor::create(setup->compositor);
  if (!comp) return cli::report(comp.error());

  nlohmann::json auto_f = nullptr;
  if (setup->auto_f) {
    // One full frame with the same foveae, then the CPU search (docs/methods.md).
    render::FrameParams full = setup->frame;
    full.method = render::Method::full;
    if (auto t = comp->render(*scene, full); !t) return cli::report(t.error());
    image::MetricsOptions mo;
    mo.ppd = comp->plan(Eye::left).pixels_per_degree();
    mo.fovea = {setup->frame.eyes[0].fovea_x, setup->frame.eyes[0].fovea_y};
    mo.fovea_right = {setup->frame.eyes[1].fovea_x, setup->frame.eyes[1].fovea_y};
    auto est = image::estimate_rmfr_f(comp->read_image(), {setup->frame.eyes[0].sigma, setup->frame.eyes[1].sigma}, mo);
    if (!est) return cli::report(est.error());
    for (auto& e : setup->frame.eyes) e.fx = est->fx, e.fy = est->fy;
    auto_f = {{"fx", est->fx}, {"fy", est->fy}, {"predicted_fpsnr_db", est->predicted_fpsnr_db}, {"ms", est->ms},
              {"evaluations", est->evaluations}};
  }
  cli::Progress progress("render", static_cast<std::uint64_t>(a.warmup + a.frames), !a.json);
  std::vector<render::PassTimes> times;
  for (int i = 0; i < a.warmup + a.frames; ++i) {
    auto t = comp->render(*scene, setup->frame);
    if (!t) return cli::report(t.error());
    if (i >= a.warmup) times.push_back(*t);
    progress.update(static_cast<std::uint64_t>(i + 1));
  }
  progress.finish();
  // A scene with more material layers than the G-buffer holds is drawn without the rest.
  if (const unsigned dropped = scene->features & ~comp->material_features()) {
    scene->warnings.push_back(setup->scene + ": uses more material layers than the G-buffer holds (three); drawn without: " +
                              render::material_feature_names(dropped));
    cli::warn(scene->warnings.back());
  }
  const image::Image img = comp->read_image();
  if (Status s = image::save_png(a.out, img); !s) return cli::report(s.error());

  const render::PassTimes med = render::median_pass_times(times);
  const render::TargetMemory mem = comp->memory(setup->frame.pipeline);
  const auto pass = render::pass_names(setup->frame.pipeline);
  rusage ru{};
  ::getrusage(RUSAGE_SELF, &ru);
  nlohmann::json eyes;
  for (Eye e : kEyes) {
    const auto& f = setup->frame.eyes[static_cast<std::size_t>(e)];
    const auto b = comp->buffer_size(e);
    const render::EyePlan& plan = comp->plan(e);
    eyes[eye_name(e)] = {{"sigma", plan.method == render::Method::full ? 1.0 : f.sigma}, {"fx", f.fx}, {"fy", f.fy},
                         {"fovea", {plan.fovea.x, plan.fovea.y}}, {"buffer", {b[0], b[1]}},
                         {"shaded_samples", plan.shaded_samples()}};
    if (!plan.layers.empty()) {
      eyes[eye_name(e)]["layer_scale"] = plan.layer_scale;
      for (const render::Layer& l : plan.layers)
        eyes[eye_name(e)]["layers"].push_back({{"ecc_max_deg", std::isfinite(l.ecc_max_deg) ? nlohmann::json(l.ecc_max_deg) : nlohmann::json("inf")},
                                               {"pixel_size", l.pixel_size}, {"rect", {l.x, l.y, l.w, l.h}}});
    }
  }
  nlohmann::json j = {
      {"scene", setup->scene},
      {"triangles", scene->triangles},
      {"view", scene->view.source},
      {"warnings", scene->warnings},
      // The file's KHR_lights_punctual lights replace the rig (docs/scenes.md, "Lights").
      {"lights", scene->is_pattern()     ? nlohmann::json{{"source", "none"}, {"count", 0}}
                 : scene->lights.empty() ? nlohmann::json{{"source", "rig"}, {"count", setup->compositor.point_lights + 1}}
                                         : nlohmann::json{{"source", "file"}, {"count", scene->lights.size()}}},
      {"method", render::method_name(setup->frame.method)},
      {"pipeline", render::pipeline_name(setup->frame.pipeline)},
      {"blend_at", render::blend_at_name(setup->frame.blend_at)},
      {"blend", {{"samples", med.blend_samples}, {"layers", med.blend_layers}, {"dropped", med.blend_dropped}}},
      {"size", {comp->width(), comp->height()}},
      {"eyes", eyes},
      {"renderer", comp->renderer()},
      {"frames", a.frames},
      {"passes_ms", {{"shadow", med.shadow}, {pass[0], med.gbuffer}, {pass[1], med.mapping},
                     {"lighting", med.lighting}, {"inverse", med.inverse}, {"blend", med.blend}, {"gpu_total", med.gpu_total},
                     {"cpu_frame", med.cpu}}},
      {"targets_mb", {{"gbuffer", mb(mem.gbuffer)}, {"transformed", mb(mem.transformed)}, {"reduced", mb(mem.reduced)},
                      {"visibility", mb(mem.visibility)}, {"output", mb(mem.output)}, {"shadow", mb(mem.shadow)},
                      {"temporal", mb(mem.temporal)}, {"total", mb(mem.total())}}},
      {"textures_mb", mb(scene->texture_bytes)},
      // The shader variant and G-buffer layout the scene's materials chose (docs/scenes.md, "Materials").
      {"material_variant", {{"shader", comp->shading_variant()}, {"gbuffer_bytes_per_pixel", comp->gbuffer_bytes_per_pixel()},
                            {"variants", scene->variants}, {"variant", scene->variant}}},
      {"peak_rss_mb", static_cast<double>(ru.ru_maxrss) / 1024.0},
      {"auto_f", auto_f},
      {"head", head_json(*setup)},
      {"out", a.out}};
  std::optional<render::PipelineComparison> cmp;
  if (a.compare_pipelines) {
    auto c = render::compare_pipelines(*comp, *scene, setup->frame, a.frames);
    if (!c) return cli::report(c.error());
    cmp = *c;
    j["pipelines"] = pipelines_json(*cmp);
  }
  if (a.json) {
    cli::print_json(j);
  } else {
    std::printf("%s: %s %dx%d, %s -> %s\n", setup->scene.c_str(), render::method_name(setup->frame.method), comp->width(),
                comp->height(), comp->renderer().c_str(), a.out.c_str());
    for (Eye e : kEyes) {
      const auto b = comp->buffer_size(e);
      const render::EyePlan& plan = comp->plan(e);
      std::printf("  %-5s %s  buffer %dx%d  shaded %zu\n", eye_name(e), render::method_name(plan.method), b[0], b[1],
                  plan.shaded_samples());
    }
    std::printf("  shading %s, G-buffer %zu B/px%s%s\n", comp->shading_variant().c_str(), comp->gbuffer_bytes_per_pixel(),
                scene->variant.empty() ? "" : ", variant ", scene->variant.c_str());
    std::printf("  %s pipeline, ms (median of %d): shadow %.2f  %s %.2f  %s %.2f  lighting %.2f  inverse %.2f  blend %.2f  GPU total %.2f  CPU frame %.2f\n",
                render::pipeline_name(setup->frame.pipeline), a.frames, med.shadow, pass[0], med.gbuffer, pass[1], med.mapping,
                med.lighting, med.inverse, med.blend, med.gpu_total, med.cpu);
    if (setup->head.kind != "scene") {
      const Pose& p = setup->frame.head;
      std::printf("  head (%s): position %.4f,%.4f,%.4f m  orientation %.6f,%.6f,%.6f,%.6f\n",
                  setup->head.kind == "log" ? (setup->head.log + " at " + std::to_string(setup->head.sample_s) + " s").c_str()
                                            : "--head",
                  p.position_m.x, p.position_m.y, p.position_m.z, p.orientation.w, p.orientation.x, p.orientation.y,
                  p.orientation.z);
    }
    std::printf("  render targets %.1f MB, textures %.1f MB, peak RSS %.0f MB\n", mb(mem.total()), mb(scene->texture_bytes),
                static_cast<double>(ru.ru_maxrss) / 1024.0);
    if (cmp)
      for (render::Pipeline p : render::all_pipelines()) {
        const render::PassTimes& t = cmp->foveated[static_cast<std::size_t>(p)];
        const auto n = render::pass_names(p);
        std::printf("  %-10s full %.1f ms, %s %.1f ms: %s %.1f  %s %.1f  lighting %.1f; %.2fx the faster full, Amdahl limit %.2fx\n",
                    render::pipeline_name(p), cmp->full[static_cast<std::size_t>(p)].gpu_total,
                    render::method_name(setup->frame.method), t.gpu_total, n[0], t.gbuffer, n[1], t.mapping, t.lighting,
                    cmp->speedup(p), cmp->amdahl_limit(p));
      }
  }
  return cli::kExitOk;
}

}  // namespace

void add_render(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("render", "Render one frame (full or RMFR + EFR) to PNG, with per-pass timings");
  add_render_options(*sub, args->render);
  sub->add_option("--out,-o", args->out, "Output PNG")->required();
  sub->add_option("--frames", args->frames, "Timed frames (the median is reported)")->capture_default_str();
  sub->add_option("--warmup", args->warmup, "Untimed frames first")->capture_default_str()->check(CLI::Range(0, 1000));
  sub->add_flag("--json", args->json, "Print sizes, per-pass milliseconds and memory as JSON");
  sub->add_flag("--fill-view", args->fill_view,
                "Move the viewer along its line of sight until the scene's bounding sphere fills the view (object scenes)");
  sub->add_flag("--compare-pipelines", args->compare_pipelines,
                "Also time full and the frame through both pipelines (--frames each, interleaved): per pass, the speedup "
                "against the faster full pipeline, the Amdahl limit");
  sub->callback([args, &exit_code] { exit_code = run(*args); });
}

}  // namespace foveal::cmd

// The compositor at 2880x1600, both pipelines (G-buffer and visibility, docs/rmfr.md),
// full against RMFR + EFR in the same run, frames interleaved so machine noise hits all
// alike. Counters give the per-pass medians (the RMFR paper's Table 3) of each pipeline,
// the speedups against the faster full pipeline, the Amdahl limit the full-resolution
// pass leaves, the theoretical lighting speedup 2 / (1/σ_d² + 1/σ_nd²), each pipeline's
// render-target memory at the EFR pair, peak RSS, and the cost of folding lens
// distortion into the inverse pass (the example lens model). Then a plain scene under its
// own shader variant against the same scene under a layered one (issue 30).
//
//   build/bin/foveal_render_bench                      (Dungeon, σ_d 2, σ_nd 3, f 0.3)
//   FOVEAL_BENCH_SCENE=pattern:noise build/bin/foveal_render_bench
//   FOVEAL_BENCH_SCENE=PATH.gltf FOVEAL_BENCH_FILL=1 build/bin/foveal_render_bench
//       (an object scene with the camera moved in until the object fills the view)
//   FOVEAL_BENCH_FRAMES=N              (timed frames per configuration, medians; default 5)
//   --benchmark_filter=PlainScene      (only the plain variant against a layered one)
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "foveal/render/compositor.hpp"
#include "foveal/render/egl_context.hpp"
#include "foveal/render/pipeline_comparison.hpp"
#include "foveal/render/scene.hpp"
#include "test_support.hpp"

namespace {

using namespace foveal;
using render::Method;
using render::Pipeline;

struct Fixture {
  std::optional<gl::EglContext> ctx;
  std::optional<render::Scene> scene;
  std::optional<render::Compositor> comp;
  std::optional<render::Compositor> lens;  ///< same, with the example lens model (distortion folded)
  std::string error;

  Fixture() {
    auto c = gl::EglContext::create();
    if (!c) { error = c.error().message; return; }
    ctx.emplace(std::move(*c));
    const char* env = std::getenv("FOVEAL_BENCH_SCENE");
    auto s = render::load_scene(env ? env : test::source_path("data/scenes/Dungeon/dungeon_simplified.gltf"));
    if (!s) { error = s.error().message; return; }
    scene.emplace(std::move(*s));
    if (const char* fill = std::getenv("FOVEAL_BENCH_FILL"); fill && std::string(fill) == "1") fill_view(*scene);
    auto k = render::Compositor::create({}, gl::ShaderLoader(test::source_path("shaders")));
    if (!k) { error = k.error().message; return; }
    comp.emplace(std::move(*k));
    auto model = DisplayModel::load(test::source_path("data/display/htc_vive_pro_eye_lens.json"));
    if (!model) { error = model.error().message; return; }
    render::CompositorOptions lo;
    lo.model = *model;
    auto l = render::Compositor::create(lo, gl::ShaderLoader(test::source_path("shaders")));
    if (!l) { error = l.error().message; return; }
    lens.emplace(std::move(*l));
  }
};

// Render-target bytes a compositor holds that only ever renders `f` (what a foveald
// session on that pipeline holds).
double targets_mb(const render::Scene& s, render::FrameParams f, Pipeline p) {
  f.pipeline = p;
  auto c = render::Compositor::create({}, gl::ShaderLoader(test::source_path("shaders")));
  if (!c || !c->render(s, f)) return -1;
  return static_cast<double>(c->memory().total()) / 1e6;
}

int frames() {
  const char* e = std::getenv("FOVEAL_BENCH_FRAMES");
  const int n = e ? std::atoi(e) : 5;
  return n > 0 ? n : 5;
}

void BM_PipelinesFullVsRmfrEfr(benchmark::State& state) {
  static Fixture f;
  if (!f.error.empty()) {
    state.SkipWithError(f.error.c_str());
    return;
  }
  const double sigma_d = 2.0, sigma_nd = 3.0;
  const render::FrameParams rmfr = render::efr_frame(Method::rmfr, Eye::right, sigma_d, sigma_nd, 0.3, 0.3);
  for (auto _ : state) {
    auto cmp = render::compare_pipelines(*f.comp, *f.scene, rmfr, frames());
    if (!cmp) {
      state.SkipWithError(cmp.error().message.c_str());
      return;
    }
    // Lens correction folded into the inverse pass: its extra cost, no extra pass.
    std::vector<render::PassTimes> tl;
    for (int i = 0; i <= frames(); ++i) {
      auto l = f.lens->render(*f.scene, rmfr);
      if (!l) {
        state.SkipWithError(l.error().message.c_str());
        return;
      }
      if (i > 0) tl.push_back(*l);
    }
    using PT = render::PassTimes;
    // "fullres": the G-buffer or visibility pass; "mapping": the mapping or material pass.
    const std::pair<const char*, double PT::*> passes[] = {{"shadow", &PT::shadow},   {"fullres", &PT::gbuffer},
                                                           {"mapping", &PT::mapping}, {"lighting", &PT::lighting},
                                                           {"inverse", &PT::inverse}, {"gpu_total", &PT::gpu_total},
                                                           {"cpu_frame", &PT::cpu}};
    for (Pipeline p : render::all_pipelines()) {
      const std::string n = render::pipeline_name(p);
      const std::size_t i = static_cast<std::size_t>(p);
      for (const auto& [name, field] : passes) {
        state.counters[n + "_full_" + name + "_ms"] = cmp->full[i].*field;
        state.counters[n + "_rmfr_" + name + "_ms"] = cmp->foveated[i].*field;
      }
      state.counters[n + "_rmfr_speedup"] = cmp->speedup(p);
      state.counters[n + "_rmfr_fullres_share"] = cmp->fullres_share(p);
      state.counters[n + "_rmfr_amdahl_limit"] = cmp->amdahl_limit(p);
      state.counters[n + "_rmfr_lighting_speedup"] = cmp->full[i].lighting / cmp->foveated[i].lighting;
      state.counters[n + "_targets_MB"] = targets_mb(*f.scene, rmfr, p);
    }
    state.counters["lighting_theory"] = 2.0 / (1.0 / (sigma_d * sigma_d) + 1.0 / (sigma_nd * sigma_nd));
    const PT ml = render::median_pass_times(tl);
    state.counters["gbuffer_rmfr_lens_inverse_ms"] = ml.inverse;
    state.counters["gbuffer_rmfr_lens_gpu_total_ms"] = ml.gpu_total;
  }
  state.counters["textures_MB"] = static_cast<double>(f.scene->texture_bytes) / 1e6;
  rusage ru{};
  ::getrusage(RUSAGE_SELF, &ru);
  state.counters["peak_rss_MB"] = static_cast<double>(ru.ru_maxrss) / 1024.0;
  state.SetLabel(f.comp->renderer());
}
BENCHMARK(BM_PipelinesFullVsRmfrEfr)->Unit(benchmark::kMillisecond)->Iterations(1);

// A plain metal-rough scene (Dungeon) pays nothing for the material features it does not
// use (docs/scenes.md, "Materials"): its own variant against the same scene drawn as if
// its materials used clearcoat, specular and sheen (three layer targets, the code of
// each compiled in: what one shader for every scene would cost it; the layers' factors
// are 0, so the picture is the same). Two compositors, frames interleaved, RMFR + EFR and
// full through both pipelines; counters: GPU frame medians, the layered / plain ratio
// and each one's render-target memory.
void BM_PlainSceneVariantAgainstLayered(benchmark::State& state) {
  static Fixture f;
  if (!f.error.empty()) {
    state.SkipWithError(f.error.c_str());
    return;
  }
  const unsigned layered = render::feature_clearcoat | render::feature_specular | render::feature_sheen;
  auto plain_comp = render::Compositor::create({}, gl::ShaderLoader(test::source_path("shaders")));
  auto layered_comp = render::Compositor::create({}, gl::ShaderLoader(test::source_path("shaders")));
  if (!plain_comp || !layered_comp) {
    state.SkipWithError("compositor");
    return;
  }
  const unsigned own = f.scene->features;
  for (auto _ : state) {
    for (Pipeline p : render::all_pipelines())
      for (Method m : {Method::full, Method::rmfr}) {
        render::FrameParams fp = m == Method::full ? render::FrameParams{} : render::efr_frame(m, Eye::right, 2.0, 3.0, 0.3, 0.3);
        fp.pipeline = p;
        std::vector<double> a, b;
        for (int i = 0; i <= frames(); ++i) {
          f.scene->features = own;
          auto ta = plain_comp->render(*f.scene, fp);
          f.scene->features = own | layered;
          auto tb = layered_comp->render(*f.scene, fp);
          f.scene->features = own;
          if (!ta || !tb) {
            state.SkipWithError((ta ? tb.error() : ta.error()).message.c_str());
            return;
          }
          if (i > 0) a.push_back(ta->gpu_total), b.push_back(tb->gpu_total);  // the first compiles
        }
        std::sort(a.begin(), a.end()), std::sort(b.begin(), b.end());
        const std::string n = std::string(render::pipeline_name(p)) + "_" + render::method_name(m);
        state.counters[n + "_plain_gpu_ms"] = a[a.size() / 2];
        state.counters[n + "_layered_gpu_ms"] = b[b.size() / 2];
        state.counters[n + "_layered_over_plain"] = b[b.size() / 2] / a[a.size() / 2];
        state.counters[n + "_plain_targets_MB"] = static_cast<double>(plain_comp->memory(p).total()) / 1e6;
        state.counters[n + "_layered_targets_MB"] = static_cast<double>(layered_comp->memory(p).total()) / 1e6;
      }
  }
  state.SetLabel(plain_comp->shading_variant() + " against " + layered_comp->shading_variant());
}
BENCHMARK(BM_PlainSceneVariantAgainstLayered)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();

// The compositor at 2880x1600: full against RMFR + EFR in the same run, frames
// interleaved so machine noise hits both alike. Counters give the per-pass medians
// (the RMFR paper's Table 3), the speedups, the theoretical lighting speedup
// 2 / (1/σ_d² + 1/σ_nd²), render-target memory and peak RSS, and the cost of folding
// lens distortion into the inverse pass (the example lens model).
//
//   build/bin/foveal_render_bench                      (Dungeon, σ_d 2, σ_nd 3, f 0.3)
//   FOVEAL_BENCH_SCENE=pattern:noise build/bin/foveal_render_bench
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdlib>
#include <optional>

#include "foveal/render/compositor.hpp"
#include "foveal/render/egl_context.hpp"
#include "foveal/render/scene.hpp"
#include "test_support.hpp"

namespace {

using namespace foveal;

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

void BM_FullVsRmfrEfr(benchmark::State& state) {
  static Fixture f;
  if (!f.error.empty()) {
    state.SkipWithError(f.error.c_str());
    return;
  }
  const double sigma_d = 2.0, sigma_nd = 3.0;
  const render::FrameParams full = render::efr_frame(render::Method::full, Eye::right, 1, 1, 0.3, 0.3);
  const render::FrameParams rmfr = render::efr_frame(render::Method::rmfr, Eye::right, sigma_d, sigma_nd, 0.3, 0.3);
  // One warm-up frame each: shader compilation, texture residency.
  (void)f.comp->render(*f.scene, full);
  (void)f.comp->render(*f.scene, rmfr);
  (void)f.lens->render(*f.scene, rmfr);
  std::vector<render::PassTimes> tf, tr, tl;
  for (auto _ : state) {
    auto a = f.comp->render(*f.scene, full);
    auto b = f.comp->render(*f.scene, rmfr);
    auto c = f.lens->render(*f.scene, rmfr);
    if (!a || !b || !c) {
      state.SkipWithError((!a ? a.error() : !b ? b.error() : c.error()).message.c_str());
      return;
    }
    tf.push_back(*a);
    tr.push_back(*b);
    tl.push_back(*c);
  }
  const render::PassTimes mf = render::median_pass_times(tf), mr = render::median_pass_times(tr),
                          ml = render::median_pass_times(tl);
  using PT = render::PassTimes;
  const std::pair<const char*, double PT::*> passes[] = {{"shadow", &PT::shadow},     {"gbuffer", &PT::gbuffer},
                                                         {"mapping", &PT::mapping},   {"lighting", &PT::lighting},
                                                         {"inverse", &PT::inverse},   {"gpu_total", &PT::gpu_total},
                                                         {"cpu_frame", &PT::cpu}};
  for (const auto& [name, field] : passes) {
    state.counters[std::string("full_") + name + "_ms"] = mf.*field;
    state.counters[std::string("rmfr_") + name + "_ms"] = mr.*field;
  }
  // Lens correction folded into the inverse pass: its extra cost, no extra pass.
  state.counters["rmfr_lens_inverse_ms"] = ml.inverse;
  state.counters["rmfr_lens_gpu_total_ms"] = ml.gpu_total;
  state.counters["lighting_speedup"] = mf.lighting / mr.lighting;
  state.counters["lighting_theory"] = 2.0 / (1.0 / (sigma_d * sigma_d) + 1.0 / (sigma_nd * sigma_nd));
  state.counters["gpu_total_speedup"] = mf.gpu_total / mr.gpu_total;
  state.counters["cpu_frame_speedup"] = mf.cpu / mr.cpu;
  state.counters["targets_MB"] = static_cast<double>(f.comp->memory().total()) / 1e6;
  state.counters["textures_MB"] = static_cast<double>(f.scene->texture_bytes) / 1e6;
  rusage ru{};
  ::getrusage(RUSAGE_SELF, &ru);
  state.counters["peak_rss_MB"] = static_cast<double>(ru.ru_maxrss) / 1024.0;
  state.SetLabel(f.comp->renderer());
}
BENCHMARK(BM_FullVsRmfrEfr)->Unit(benchmark::kMillisecond)->Iterations(5);

}  // namespace

BENCHMARK_MAIN();

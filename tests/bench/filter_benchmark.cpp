// The whole gaze chain per sample (validation, fallbacks, saccade detection, 1€, pixel
// mapping, both eyes) on pre-generated synthetic samples: samples per second, one core.
#include <benchmark/benchmark.h>

#include <vector>

#include "foveal/drivers/synthetic_source.hpp"
#include "foveal/runtime/gaze_pipeline.hpp"

namespace {

const std::vector<foveal::GazeSample>& samples() {
  static const std::vector<foveal::GazeSample> v = [] {
    foveal::SyntheticOptions o;
    o.duration_s = 120;
    foveal::SyntheticGenerator gen(o);
    std::vector<foveal::GazeSample> out;
    foveal::GazeSample s;
    foveal::GazeTruth t;
    while (gen.next(s, t)) out.push_back(s);
    return out;
  }();
  return v;
}

void BM_GazePipeline(benchmark::State& state) {
  const auto& in = samples();
  foveal::GazePipeline pipe(foveal::DisplayModel::vive_pro_eye(), foveal::FilterConfig{});
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(pipe.update(in[i]));
    if (++i == in.size()) i = 0;  // wraps: a time jump, handled like a dropout
  }
  state.counters["samples_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["ns_per_sample"] = benchmark::Counter(static_cast<double>(state.iterations()),
                                                       benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_GazePipeline);

}  // namespace

BENCHMARK_MAIN();

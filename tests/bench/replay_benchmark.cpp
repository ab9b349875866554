// Replay throughput at speed 0: samples read from a native gaze log on disk, parsed,
// validated and delivered through the GazeSource interface, on one core.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <string>

#include "foveal/core/gaze_log.hpp"
#include "foveal/drivers/replay_source.hpp"
#include "foveal/drivers/synthetic_source.hpp"

namespace {

// A synthetic stress log written once per process: every field present in both eyes,
// and values with 8-10 significant digits (real trackers write 7).
const std::string& bench_log() {
  static const std::string path = [] {
    std::string p = "/tmp/foveal-bench-replay-" + std::to_string(::getpid()) + ".csv";
    foveal::SyntheticOptions o;
    o.duration_s = 600;  // 72k samples
    foveal::SyntheticGenerator gen(o);
    foveal::GazeLogHeader h;
    h.rate_hz = o.rate_hz;
    auto w = foveal::GazeLogWriter::create(p, h);
    foveal::GazeSample s;
    foveal::GazeTruth t;
    while (gen.next(s, t)) (void)w->write(s);
    (void)w->commit();
    std::atexit([] { std::remove(bench_log().c_str()); });
    return p;
  }();
  return path;
}

void BM_ReplaySyntheticStress(benchmark::State& state) {
  const std::string& path = bench_log();
  std::uint64_t samples = 0;
  for (auto _ : state) {
    foveal::ReplayOptions o;
    o.path = path;
    o.speed = 0;
    foveal::ReplaySource src(o);
    if (!src.open() || !src.start()) {
      state.SkipWithError("cannot open the benchmark log");
      return;
    }
    for (;;) {
      foveal::ReadResult r = src.next(std::chrono::milliseconds(1));
      if (r.status != foveal::ReadStatus::sample) break;
      benchmark::DoNotOptimize(r.sample);
      ++samples;
    }
  }
  state.counters["samples_per_s"] = benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ReplaySyntheticStress)->Unit(benchmark::kMillisecond)->UseRealTime();

// The bundled real Vive Pro Eye recording (7-digit SRanipal values, 13% invalid rows),
// looped: the acceptance figure (>= 5 M samples/s).
void BM_ReplayViveRecording(benchmark::State& state) {
  std::uint64_t samples = 0;
  for (auto _ : state) {
    foveal::ReplayOptions o;
    o.path = std::string(FOVEAL_SOURCE_DIR) + "/data/gaze/vive_pro_eye_TESTNA01.csv";
    o.speed = 0;
    o.loop = true;
    foveal::ReplaySource src(o);
    if (!src.open() || !src.start()) {
      state.SkipWithError("cannot open the bundled log");
      return;
    }
    for (int i = 0; i < 100000; ++i) {
      foveal::ReadResult r = src.next(std::chrono::milliseconds(1));
      benchmark::DoNotOptimize(r.sample);
    }
    samples += 100000;
  }
  state.counters["samples_per_s"] = benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ReplayViveRecording)->Unit(benchmark::kMillisecond)->UseRealTime();

// The reader alone, to separate parsing from delivery.
void BM_GazeLogRead(benchmark::State& state) {
  const std::string& path = bench_log();
  std::uint64_t samples = 0;
  for (auto _ : state) {
    auto r = foveal::GazeLogReader::open(path);
    foveal::GazeSample s;
    while (true) {
      auto got = r->next(s);
      if (!got || !*got) break;
      benchmark::DoNotOptimize(s);
      ++samples;
    }
  }
  state.counters["samples_per_s"] = benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_GazeLogRead)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SyntheticGenerate(benchmark::State& state) {
  std::uint64_t samples = 0;
  for (auto _ : state) {
    foveal::SyntheticOptions o;
    o.duration_s = 60;
    foveal::SyntheticGenerator gen(o);
    foveal::GazeSample s;
    foveal::GazeTruth t;
    while (gen.next(s, t)) {
      benchmark::DoNotOptimize(s);
      ++samples;
    }
  }
  state.counters["samples_per_s"] = benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SyntheticGenerate)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

// The gaze thread with a real source (synthetic, as fast as possible).
#include <gtest/gtest.h>

#include <atomic>

#include "foveal/drivers/synthetic_source.hpp"
#include "foveal/runtime/gaze_loop.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

SyntheticOptions fast(double seconds) {
  SyntheticOptions o;
  o.duration_s = seconds;
  o.speed = 0;
  return o;
}

FoveaFrame tag(const GazeSample& s, float x) {
  FoveaFrame f;
  f.t_ns = s.t_ns;
  f.eyes[0].px = {x, 1.0f};
  return f;
}

void wait_finished(const GazeLoop& loop) {
  test::eventually([&] { return loop.finished(); }, test::kEventWithinMs, 1);
}

TEST(GazeLoop, PublishesEverySampleUntilTheSourceEnds) {
  SyntheticSource src(fast(10));  // 1200 samples
  ASSERT_TRUE(src.open());
  ASSERT_TRUE(src.start());
  std::atomic<int> observed{0};
  GazeLoop loop(src, [](const GazeSample& s) { return tag(s, 5.0f); },
                [&](const GazeSample&, const FoveaFrame&) { ++observed; });
  loop.start();
  wait_finished(loop);
  ASSERT_TRUE(loop.finished());
  loop.stop();
  const GazeLoopStats st = loop.stats();
  EXPECT_TRUE(st.ended);
  EXPECT_FALSE(st.failed);
  EXPECT_EQ(st.samples, 1200u);
  EXPECT_EQ(observed.load(), 1200);
  EXPECT_GT(st.latency_p99_ns, 0);
  FoveaFrame f;
  ASSERT_TRUE(loop.latest().load(f));
  EXPECT_FLOAT_EQ(f.eyes[0].px.x, 5.0f);
}

TEST(GazeLoop, ARenderThreadReadsWhileTheGazeThreadWrites) {
  SyntheticOptions o = fast(30);
  SyntheticSource src(o);
  ASSERT_TRUE(src.open());
  ASSERT_TRUE(src.start());
  GazeLoop loop(src, [](const GazeSample& s) {
    FoveaFrame f;
    f.t_ns = s.t_ns;
    f.eyes[0].px = {static_cast<float>(s.t_ns % 1000), static_cast<float>(s.t_ns % 1000)};  // x == y always
    return f;
  });
  loop.start();
  int reads = 0, torn = 0;
  // At least one read even when a loaded machine lets the gaze thread finish first.
  do {
    FoveaFrame f;
    if (loop.latest().load(f)) {
      ++reads;
      if (f.eyes[0].px.x != f.eyes[0].px.y) ++torn;
    }
  } while (!loop.finished());
  loop.stop();
  EXPECT_GT(reads, 0);
  EXPECT_EQ(torn, 0);
}

TEST(GazeLoop, PauseSkipsAndSetMapperTakesEffect) {
  SyntheticOptions o;
  o.duration_s = 0;  // endless
  o.speed = 50;      // 6000 samples/s: fast but paced
  SyntheticSource src(o);
  ASSERT_TRUE(src.open());
  ASSERT_TRUE(src.start());
  GazeLoop loop(src, [](const GazeSample& s) { return tag(s, 1.0f); });
  loop.start();
  loop.set_paused(true);
  // The pause is in once the stats count a skipped sample: every sample published before
  // it is counted in that snapshot, and none after it (waited for, not slept out).
  ASSERT_TRUE(test::eventually([&] { return loop.stats().skipped > 0; }));
  const GazeLoopStats paused = loop.stats();
  const std::uint64_t during_pause = paused.samples;
  ASSERT_TRUE(test::eventually([&] { return loop.stats().skipped > paused.skipped; }));  // a later snapshot
  EXPECT_EQ(loop.stats().samples, during_pause);
  loop.set_paused(false);
  loop.set_mapper([](const GazeSample& s) { return tag(s, 2.0f); });
  // The new mapper's first sample, and the stats that count it (published every
  // kStatsPeriod, after the fovea), are waited for, not expected by a set time.
  FoveaFrame f;
  EXPECT_TRUE(test::eventually(
      [&] { return loop.latest().load(f) && f.eyes[0].px.x == 2.0f && loop.stats().samples > during_pause; }));
  ASSERT_TRUE(loop.latest().load(f));
  EXPECT_FLOAT_EQ(f.eyes[0].px.x, 2.0f);
  EXPECT_GT(loop.stats().samples, during_pause);
  const TimeNs t0 = monotonic_now_ns();
  loop.stop();
  EXPECT_LT(monotonic_now_ns() - t0, test::kReturnsWithinNs);  // stop() returns (its poll has a timeout)
  EXPECT_FALSE(loop.stats().ended);
}

}  // namespace
}  // namespace foveal

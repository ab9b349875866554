// foveald's frame pacing and gaze-to-photon record, without GL (docs/latency.md).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "csv_rows.hpp"
#include "frame_latency.hpp"
#include "frame_pacer.hpp"

namespace foveal::daemon {
namespace {

constexpr TimeNs kPeriod = 11'111'111;  // 90 Hz

TEST(FramePacer, AsapStartsAtOnceAndTargetsTheNextRefreshItCanMake) {
  FramePacer p(Pacing::asap, 90);
  const FramePlan first = p.plan(1000, std::nullopt);
  EXPECT_EQ(first.start_ns, 1000);
  p.shown(0, 8 * kNsPerSec, 8 * kNsPerSec, 0);  // the first frame (shaders compiled): not counted
  p.shown(0, 3 * kNsPerMs, 10 * kNsPerMs, 0);    // 3 ms of work
  const FramePlan next = p.plan(10 * kNsPerMs + 500, 10 * kNsPerMs);
  EXPECT_EQ(next.start_ns, 10 * kNsPerMs + 500);
  EXPECT_EQ(next.display_target_ns, 10 * kNsPerMs + kPeriod);
}

TEST(FramePacer, JitStartsAsLateAsTheWorkAndMarginAllow) {
  FramePacer p(Pacing::jit, 90);
  p.shown(0, 8 * kNsPerSec, 8 * kNsPerSec, 0);  // the first frame: not counted
  p.shown(0, 3 * kNsPerMs, 10 * kNsPerMs, 0);
  const TimeNs shown = 100 * kNsPerMs;
  const FramePlan plan = p.plan(shown + kNsPerMs, shown);
  EXPECT_EQ(plan.display_target_ns, shown + kPeriod);
  EXPECT_EQ(plan.start_ns, shown + kPeriod - 3 * kNsPerMs - 2 * kNsPerMs);  // work 3 ms, margin 2 ms
  // Too late for that refresh: the one after.
  const FramePlan late = p.plan(shown + kPeriod - 4 * kNsPerMs, shown);
  EXPECT_EQ(late.display_target_ns, shown + 2 * kPeriod);
}

TEST(FramePacer, AMissGrowsTheMarginAndFramesOnTimeShrinkItSlowly) {
  FramePacer p(Pacing::jit, 90);
  EXPECT_DOUBLE_EQ(p.margin_ms(), 2.0);
  p.shown(0, 9 * kNsPerSec, 9 * kNsPerSec, kPeriod);  // the first frame, 9 s late: not a miss
  EXPECT_EQ(p.misses(), 0u);
  EXPECT_DOUBLE_EQ(p.margin_ms(), 2.0);
  p.shown(0, kNsPerMs, kPeriod + kPeriod, kPeriod);  // a refresh late
  EXPECT_EQ(p.misses(), 1u);
  EXPECT_DOUBLE_EQ(p.margin_ms(), 3.0);
  for (int i = 0; i < 30; ++i) p.shown(0, kNsPerMs, kPeriod, kPeriod);
  EXPECT_DOUBLE_EQ(p.margin_ms(), 2.75);
  for (int i = 0; i < 3000; ++i) p.shown(0, kNsPerMs, kPeriod, kPeriod);
  EXPECT_DOUBLE_EQ(p.margin_ms(), 1.0);  // the floor
  p.shown(0, kPeriod + 40 * kNsPerMs, 2 * kPeriod, kPeriod);  // one hitch, 40 ms late: one step
  EXPECT_DOUBLE_EQ(p.margin_ms(), 2.0);
  for (int i = 0; i < 99; ++i) p.shown(0, kNsPerMs, 3 * kPeriod, kPeriod);
  EXPECT_LE(p.margin_ms(), 11.2);  // never more than a period
  EXPECT_EQ(p.json()["misses"], 101);
}

TEST(FramePacer, WithoutARefreshItNeverWaits) {
  FramePacer p(Pacing::jit, 0);
  p.shown(0, 5 * kNsPerMs, 6 * kNsPerMs, 0);
  EXPECT_EQ(p.plan(777, 6 * kNsPerMs).start_ns, 777);
  EXPECT_FALSE(parse_pacing("soon"));
  EXPECT_EQ(*parse_pacing("jit"), Pacing::jit);
}

TEST(FrameLatency, ThePartsAddUpToGazeToPhotonInTheCsv) {
  FrameLatency f;
  f.sample_t_ns = 1'000'000'000;
  f.sample_device_t_ns = 8'333'333;
  f.arrival_ns = 1'000'412'345;
  f.start_ns = 1'003'000'000;
  f.latch_ns = 1'004'100'007;
  f.gpu_done_ns = 1'009'999'999;
  f.shown_ns = 1'011'111'111;
  f.display_target_ns = 1'011'111'111;
  const std::vector<std::string> cells = test::csv_cells(f.csv_cells());
  ASSERT_EQ(cells.size(), test::csv_cells(FrameLatency::csv_header()).size());
  EXPECT_EQ(cells[0], "8333333");
  const double total = std::stod(cells[7]);
  double parts = 0;
  for (std::size_t i = 8; i < 12; ++i) parts += std::stod(cells[i]);
  EXPECT_NEAR(total, 11.111, 0.001);
  EXPECT_NEAR(parts, total, 0.004);
  LatencyStats s;
  s.add(f);
  const nlohmann::json j = s.json("page_flip");
  EXPECT_EQ(j["frames"], 1);
  EXPECT_NEAR(j["gaze_to_photon_ms"]["max"].get<double>(), 11.111, 0.01);
}

TEST(FrameLatency, AFrameWithoutASampleHasEmptySampleCellsAndIsNotCounted) {
  FrameLatency f;
  f.start_ns = 5, f.latch_ns = 6, f.gpu_done_ns = 7, f.shown_ns = 8;
  const std::vector<std::string> cells = test::csv_cells(f.csv_cells());
  ASSERT_EQ(cells.size(), test::csv_cells(FrameLatency::csv_header()).size());
  EXPECT_EQ(cells[0], "");
  EXPECT_EQ(cells[5], "8");
  EXPECT_EQ(cells[7], "");
  LatencyStats s;
  s.add(f);
  EXPECT_EQ(s.json("gpu_done")["frames"], 0);
}

}  // namespace
}  // namespace foveal::daemon

#include <gtest/gtest.h>

#include <cmath>

#include "foveal/runtime/latency_histogram.hpp"

namespace foveal {
namespace {

TEST(LatencyHistogram, PercentilesWithinTwoPercent) {
  LatencyHistogram h;
  for (std::int64_t v = 1; v <= 100000; ++v) h.add(v * 1000);  // 1 us .. 100 ms, uniform
  EXPECT_EQ(h.count(), 100000u);
  EXPECT_EQ(h.max(), 100000000);
  EXPECT_NEAR(static_cast<double>(h.percentile(0.5)), 50e6, 50e6 * 0.02);
  EXPECT_NEAR(static_cast<double>(h.percentile(0.99)), 99e6, 99e6 * 0.02);
  EXPECT_LE(h.percentile(1.0), h.max());
}

TEST(LatencyHistogram, EveryBucketGivesAValueInsideIt) {
  for (std::int64_t v : {std::int64_t{63}, std::int64_t{64}, std::int64_t{100}, std::int64_t{127}, std::int64_t{128},
                         std::int64_t{1000}, std::int64_t{123456789}}) {
    LatencyHistogram h;
    h.add(v);
    h.add(v + 1000000000);  // a larger max, so the bucket value is not clamped
    const std::int64_t p = h.percentile(0.0);
    EXPECT_GE(p, v - v / 50 - 1) << v;
    EXPECT_LE(p, v + v / 50 + 1) << v;
  }
}

TEST(LatencyHistogram, SmallValuesAreExactAndEmptyIsZero) {
  LatencyHistogram h;
  EXPECT_EQ(h.percentile(0.5), 0);
  for (int i = 0; i < 10; ++i) h.add(7);
  h.add(-5);  // clock oddities land in bucket 0, never crash
  EXPECT_EQ(h.percentile(0.5), 7);
  EXPECT_EQ(h.percentile(0.0), 0);
}

}  // namespace
}  // namespace foveal

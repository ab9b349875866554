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

// RMFR's per-axis mapping: edges to edges, fovea fixed, inverse of each other, no
// division by the border distance, monotonic, continuous at the fovea.
#include <gtest/gtest.h>

#include <cmath>

#include "foveal/rmfr_mapping.hpp"

using namespace foveal::rmfr;

namespace {
const double kFoveae[] = {0.0, 1e-6, 0.1, 0.25, 0.5, 0.73, 0.999999, 1.0};
const double kFs[] = {0.01, 0.05, 0.3, 1.0, 10.0};
}  // namespace

TEST(RmfrMapping, EdgesMapToEdgesAndFoveaIsFixed) {
  for (double c : kFoveae)
    for (double f : kFs) {
      EXPECT_NEAR(rmfr_forward(0.0, c, f), 0.0, 1e-12) << c << " " << f;
      EXPECT_NEAR(rmfr_forward(1.0, c, f), 1.0, 1e-12) << c << " " << f;
      EXPECT_DOUBLE_EQ(rmfr_forward(c, c, f), c);
      EXPECT_NEAR(rmfr_inverse(0.0, c, f), 0.0, 1e-12);
      EXPECT_NEAR(rmfr_inverse(1.0, c, f), 1.0, 1e-12);
      EXPECT_DOUBLE_EQ(rmfr_inverse(c, c, f), c);
    }
}

TEST(RmfrMapping, InverseUndoesForwardEverywhereIncludingBorderFoveae) {
  for (double c : kFoveae)
    for (double f : kFs)
      for (int i = 0; i <= 1000; ++i) {
        const double p = i / 1000.0;
        const double u = rmfr_forward(p, c, f);
        ASSERT_TRUE(std::isfinite(u)) << "p " << p << " c " << c << " f " << f;
        ASSERT_GE(u, -1e-12);
        ASSERT_LE(u, 1.0 + 1e-12);
        ASSERT_NEAR(rmfr_inverse(u, c, f), p, 1e-9) << "p " << p << " c " << c << " f " << f;
      }
}

TEST(RmfrMapping, MonotonicSoNoFoldsOrHoles) {
  for (double c : kFoveae)
    for (double f : kFs) {
      double prev = -1;
      for (int i = 0; i <= 2000; ++i) {
        const double u = rmfr_forward(i / 2000.0, c, f);
        ASSERT_GE(u, prev) << "c " << c << " f " << f;
        prev = u;
      }
    }
}

TEST(RmfrMapping, DensityAtFoveaAndEdgeMatchesTheDesignFormulas) {
  // du/dp = (f + D)/f at the fovea and f/(f + D) at the edge (normalised units).
  const double c = 0.3, f = 0.3, h = 1e-7;
  const double right = (rmfr_forward(c + h, c, f) - c) / h, left = (c - rmfr_forward(c - h, c, f)) / h;
  EXPECT_NEAR(right, (f + 0.7) / f, 1e-4);
  EXPECT_NEAR(left, (f + 0.3) / f, 1e-4);
  const double edge = (1.0 - rmfr_forward(1.0 - h, c, f)) / h;
  EXPECT_NEAR(edge, f / (f + 0.7), 1e-4);
}

TEST(RmfrMapping, SigmaOneIsTheIdentity) {
  const double f = rmfr_effective_f(0.3, 1.0, 0.5);
  for (double c : kFoveae)
    for (int i = 0; i <= 100; ++i) {
      EXPECT_NEAR(rmfr_forward(i / 100.0, c, f), i / 100.0, 1e-12);
      EXPECT_NEAR(rmfr_inverse(i / 100.0, c, f), i / 100.0, 1e-12);
    }
  EXPECT_EQ(rmfr_effective_f(0.3, 2.0, 0.5), 0.3);
}

TEST(RmfrMapping, BufferSizesAndFoveaSanitising) {
  EXPECT_EQ(rmfr_buffer_size(1440, 2.0), 720);
  EXPECT_EQ(rmfr_buffer_size(1440, 3.0), 480);
  EXPECT_EQ(rmfr_buffer_size(1600, 2.6), 615);
  EXPECT_EQ(rmfr_buffer_size(3, 100.0), 1);
  EXPECT_EQ(sanitize_fovea(NAN), 0.5);
  EXPECT_EQ(sanitize_fovea(INFINITY), 0.5);
  EXPECT_EQ(sanitize_fovea(-3.0), 0.0);
  EXPECT_EQ(sanitize_fovea(7.0), 1.0);
  EXPECT_EQ(sanitize_fovea(0.25), 0.25);
}

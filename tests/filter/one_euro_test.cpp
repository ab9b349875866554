#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "foveal/runtime/one_euro.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

// The reference implementation's output (tests/filter/data, SOURCE.md there): 120 Hz, mincutoff 1,
// beta 0.1, dcutoff 1, timestamps in seconds; every row within 1e-4.
TEST(OneEuro, ReproducesTheReferenceGroundTruth) {
  std::ifstream in(test::source_path("tests/filter/data/oneeuro_groundtruth.csv"));
  ASSERT_TRUE(in) << "missing tests/filter/data/oneeuro_groundtruth.csv";
  std::string line;
  std::getline(in, line);
  ASSERT_EQ(line, "timestamp,signal,noisy,filtered");
  OneEuroFilter f({1.0, 0.1, 1.0});
  int rows = 0;
  double worst = 0;
  while (std::getline(in, line)) {
    double t, signal, noisy, expected;
    char c;
    std::istringstream row(line);
    ASSERT_TRUE(row >> t >> c >> signal >> c >> noisy >> c >> expected) << line;
    const double got = f.filter(noisy, t, 120.0);
    worst = std::max(worst, std::fabs(got - expected));
    ASSERT_NEAR(got, expected, 1e-4) << "row " << rows + 1 << " t=" << t;
    ++rows;
  }
  EXPECT_GT(rows, 100);
  std::printf("1-euro conformance: %d rows, worst |error| %.3g\n", rows, worst);
}

TEST(OneEuro, ResetStartsOverWithoutMemory) {
  OneEuroFilter f({1.0, 0.0, 1.0});
  for (int i = 0; i < 10; ++i) f.filter(10.0, i / 120.0, 120.0);
  f.reset(-5.0, 0.1);
  EXPECT_DOUBLE_EQ(f.value(), -5.0);
  EXPECT_DOUBLE_EQ(f.speed(), 0.0);
  const double next = f.filter(-5.0, 0.1 + 1 / 120.0, 120.0);
  EXPECT_DOUBLE_EQ(next, -5.0);
}

}  // namespace
}  // namespace foveal

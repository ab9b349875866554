// The acceptance figures on synthetic scanpaths with ground truth at 0.5 deg RMS noise.
#include <gtest/gtest.h>

#include "foveal/tools/filter_score.hpp"

namespace foveal {
namespace {

SyntheticOptions scanpath(std::uint64_t seed) {
  SyntheticOptions o;
  o.seed = seed;
  o.duration_s = 120;
  o.noise_deg = 0.5;
  return o;
}

class PipelineOnSynthetic : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(PipelineOnSynthetic, MeetsTheAcceptanceFigures) {
  const FilterScore s = score_pipeline(scanpath(GetParam()), FilterConfig{});
  RecordProperty("onset_f1", std::to_string(s.onset_f1));
  std::printf("seed %llu: saccades %d, onset P %.3f R %.3f F1 %.3f, jitter raw %.3f filtered %.3f (%.2fx), "
              "lag %.2f ms, landed %.3f\n",
              static_cast<unsigned long long>(GetParam()), s.saccades, s.onset_precision, s.onset_recall, s.onset_f1,
              s.raw_fixation_rms_deg, s.filtered_fixation_rms_deg, s.raw_fixation_rms_deg / s.filtered_fixation_rms_deg,
              s.mean_fixation_lag_ms, s.landing_within_1deg);
  EXPECT_GT(s.saccades, 100);
  EXPECT_GE(s.onset_f1, 0.95);
  EXPECT_GE(s.raw_fixation_rms_deg / s.filtered_fixation_rms_deg, 3.0);
  EXPECT_LE(s.mean_fixation_lag_ms, 10.0);
  EXPECT_GE(s.landing_within_1deg, 0.95);
  EXPECT_FALSE(s.any_nan);
}

INSTANTIATE_TEST_SUITE_P(Seeds, PipelineOnSynthetic, ::testing::Values(1u, 2u, 3u));

}  // namespace
}  // namespace foveal

// foveal predict-eval end to end: the figures of docs/results/latency/prediction.md.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_support.hpp"

namespace foveal {
namespace {

TEST(PredictEvalCli, ReportsEveryColumnAndPredictionBeatsTheFilterInPursuit) {
  auto r = test::run(test::bin("foveal") + " predict-eval " + test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv") +
                     " --latency-ms 11,45 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["pooled"].size(), 2u);
  EXPECT_EQ(j["logs"].size(), 1u);
  for (const auto& l : j["pooled"]) {
    for (const char* truth : {"recorded", "smoothed"}) {
      const auto& t = l["truth"][truth];
      for (const char* phase : {"all", "fixation", "pursuit", "saccade", "saccade_onset"})
        for (const char* shown : {"none", "filter", "filter_predict_ms", "predict"}) {
          ASSERT_TRUE(t[phase].contains(shown)) << phase << " " << shown;
          EXPECT_EQ(t[phase][shown]["n"], t[phase]["none"]["n"]) << "the same samples in every column";
        }
      EXPECT_GT(t["pursuit"]["filter"]["n"].get<int>(), 100);
      // What the prediction is for: the filter trails a pursuit, the prediction less.
      EXPECT_LT(t["pursuit"]["predict"]["p50_deg"].get<double>(), t["pursuit"]["filter"]["p50_deg"].get<double>());
    }
  }
}

TEST(PredictEvalCli, BadArgumentsAreRefusedWithNoOutput) {
  const std::string log = test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv");
  for (const std::string& args : {log + " --latency-ms 0", log + " --latency-ms 11,500", log + " --max-horizon-ms -3",
                                  log + " /nonexistent/log.csv"}) {
    auto r = test::run(test::bin("foveal") + " predict-eval " + args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_TRUE(r.out.empty()) << args << ": " << r.out;
    EXPECT_FALSE(r.err.empty()) << args;
  }
}

}  // namespace
}  // namespace foveal

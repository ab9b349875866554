// foveal predict-eval end to end: the figures of docs/results/latency/prediction.md.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <sstream>
#include <string>
#include <vector>

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

// Issue 38, item 16: a log with no valid sample printed 0.00° errors with exit 0.
TEST(PredictEvalCli, NothingEvaluatedIsRefusedNotReportedAsZeroError) {
  test::TempDir d;
  // The bundled recording's first 200 samples with both eyes marked invalid.
  std::istringstream in(test::read_file(test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv")));
  std::string line, out;
  int rows = 0;
  while (std::getline(in, line) && rows < 200) {
    if (line.empty() || line[0] == '#' || line.rfind("t_ns", 0) == 0) {
      out += line + "\n";
      continue;
    }
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) f.push_back(c);
    if (line.back() == ',') f.push_back("");
    ASSERT_GT(f.size(), 10u);
    f[1] = f[10] = "0";  // left_valid, right_valid: nothing of either eye
    for (std::size_t i : {2, 3, 4, 5, 6, 7, 8, 9, 11, 12, 13, 14, 15, 16, 17, 18}) f[i].clear();
    std::string joined;
    for (std::size_t i = 0; i < f.size(); ++i) joined += (i ? "," : "") + f[i];
    out += joined + "\n";
    ++rows;
  }
  test::write_file(d.path("invalid.csv"), out);
  for (const char* json : {"", " --json"}) {
    auto r = test::run(test::bin("foveal") + " predict-eval " + d.path("invalid.csv") + " --latency-ms 11,45" + json);
    EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_NE(r.err.find("predict-eval: no sample could be evaluated at L = 11 ms, 45 ms"), std::string::npos) << r.err;
  }
}

// Issue 38, item 16: each latency keeps every sample's errors; 3,000 of them took 2.6 GB.
TEST(PredictEvalCli, AtMostThirtyTwoLatencies) {
  const std::string log = test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv");
  std::string many;
  for (int i = 1; i <= 33; ++i) many += (i > 1 ? "," : "") + std::to_string(i);
  auto r = test::run(test::bin("foveal") + " predict-eval " + log + " --latency-ms " + many);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(r.out.empty());
  EXPECT_NE(r.err.find("--latency-ms: 33 latencies, at most 32 in one run"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace foveal

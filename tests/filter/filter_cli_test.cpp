// foveal replay and foveal filter-chart end to end.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "test_support.hpp"

namespace foveal {
namespace {

TEST(ReplayCli, TracesEverySampleAndSummarises) {
  test::TempDir dir;
  auto r = test::run(test::bin("foveal") + " replay " + test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv") +
                     " --trace " + dir.path("t.csv") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["samples"], 1518);
  EXPECT_GT(j["eyes"]["left"]["saccades"].get<int>(), 0);
  EXPECT_GT(j["eyes"]["left"]["blinks"].get<int>(), 0);
  EXPECT_GT(j["eyes"]["left"]["time_lost_ms"].get<double>(), 1000.0);  // the headset came off at the end
  EXPECT_GT(j["cost_ns_per_sample"]["mean"].get<double>(), 0.0);
  const std::string trace = test::read_file(dir.path("t.csv"));
  EXPECT_EQ(std::count(trace.begin(), trace.end(), '\n'), 1519);  // header + one row per sample
  EXPECT_EQ(trace.find("nan"), std::string::npos);
}

TEST(ReplayCli, BadFilterConfigIsRejectedBeforeAnyWork) {
  test::TempDir dir;
  test::write_file(dir.path("c.json"), R"({"min_cutoff_hz": -1})");
  auto r = test::run(test::bin("foveal") + " replay " + test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv") +
                     " --config " + dir.path("c.json") + " --trace " + dir.path("t.csv"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("min_cutoff_hz"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("t.csv")));
}

// No --vive-dir: the recordings foveal ships (data/gaze/vive_pro_eye) are charted.
TEST(FilterChartCli, WritesDataAndChart) {
  test::TempDir dir;
  auto r = test::run(test::bin("foveal") + " filter-chart --seconds 20 --out " + dir.path("c") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_GE(j["synthetic"].size(), 5u);
  // The saccade-aware pipeline beats plain 1€ presets on lag after a saccade.
  double aware_lag = 1e9, plain_best = 1e9;
  for (const auto& row : j["synthetic"]) {
    if (row["method"] == "saccade_aware") aware_lag = std::min(aware_lag, row["step_lag_ms"].get<double>());
    if (row["method"] == "one_euro" && row["jitter_deg"].get<double>() < 0.3)
      plain_best = std::min(plain_best, row["step_lag_ms"].get<double>());
  }
  EXPECT_LT(aware_lag, plain_best);
  EXPECT_TRUE(std::filesystem::exists(dir.path("c/filter_chart.csv")));
  const std::string real = test::read_file(dir.path("c/filter_chart_real.csv"));
  for (const char* rec : {"TESTNA01_2D_Fist3,", "TESTNA05_360VR_Spread7,", "TESTNA15_2D_Pen3,"})
    EXPECT_NE(real.find(rec), std::string::npos) << rec << " missing from\n" << real;
  EXPECT_GT(std::filesystem::file_size(dir.path("c/filter_chart.png")), 10000u);
}

// A folder that is not there, or holds no recording, is refused before any work: no
// chart without its real-data half.
TEST(FilterChartCli, RefusesAMissingOrEmptyRecordingsFolder) {
  test::TempDir dir;
  std::filesystem::create_directory(dir.path("empty"));
  for (const std::string& vive : {dir.path("absent"), dir.path("empty")}) {
    auto r = test::run(test::bin("foveal") + " filter-chart --no-png --seconds 1 --vive-dir " + vive + " --out " +
                       dir.path("c"));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("--vive-dir " + vive), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path("c")));
  }
}

}  // namespace
}  // namespace foveal

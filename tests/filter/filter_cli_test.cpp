// foveal replay, foveal filter-chart and foveal log plot end to end.
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

// --log: the user's own native log is charted; without --vive-dir the SRanipal folder is not.
TEST(FilterChartCli, ChartsTheUsersOwnLog) {
  test::TempDir dir;
  auto r = test::run(test::bin("foveal") + " filter-chart --seconds 5 --log " + test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv") +
                     " --out " + dir.path("c"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string real = test::read_file(dir.path("c/filter_chart_real.csv"));
  EXPECT_EQ(real.rfind("recording,method,label,jitter_deg,source\n", 0), 0u) << real;
  EXPECT_NE(real.find("vive_pro_eye_TESTNA01,none,no filter,"), std::string::npos) << real;
  EXPECT_NE(real.find(",log\n"), std::string::npos) << real;
  EXPECT_EQ(real.find("TESTNA05_360VR_Spread7"), std::string::npos) << real;
  EXPECT_GT(std::filesystem::file_size(dir.path("c/filter_chart.png")), 10000u);
  // A bad log is refused before any work, naming file and line; --out is not created.
  test::write_file(dir.path("bad.csv"), "# foveal-gaze-log v1\n# rate_hz=120\nt_ns\n");
  r = test::run(test::bin("foveal") + " filter-chart --no-png --seconds 1 --log " + dir.path("bad.csv") + " --out " + dir.path("d"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(dir.path("bad.csv") + ":3"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("d")));
}

// foveal log plot: a log, its replay trace, both together; a PNG each.
TEST(LogPlotCli, PlotsALogATraceAndBoth) {
  test::TempDir dir;
  const std::string log = test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv");
  auto r = test::run(test::bin("foveal") + " replay " + log + " --trace " + dir.path("t.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const std::string& args : {log + " -o " + dir.path("log.png"), dir.path("t.csv") + " -o " + dir.path("trace.png"),
                                  log + " --trace " + dir.path("t.csv") + " --start 2 --end 9 -o " + dir.path("both.png")}) {
    r = test::run(test::bin("foveal") + " log plot " + args);
    ASSERT_EQ(r.exit_code, 0) << args << ": " << r.err;
  }
  for (const char* png : {"log.png", "trace.png", "both.png"}) {
    const std::string head = test::read_file(dir.path(png)).substr(0, 8);
    EXPECT_EQ(head, "\x89PNG\r\n\x1a\n") << png;
  }
  for (const auto& e : std::filesystem::directory_iterator(dir.path("")))
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
}

// A malformed row: exit 2, the file and the line named, no PNG. A log is checked by
// foveal's own reader; a trace by the chart script.
TEST(LogPlotCli, RejectsAMalformedRowNamingFileAndLine) {
  test::TempDir dir;
  std::string text = test::read_file(test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv"));
  std::size_t at = 0;
  for (int line = 1; line < 10; ++line) at = text.find('\n', at) + 1;  // the start of line 10
  const std::size_t field = text.find(',', at) + 1;                      // its left_valid
  text.replace(text.find(',', field) + 1, 1, "x");                      // left_dir_x starts with x
  test::write_file(dir.path("bad.csv"), text);
  auto r = test::run(test::bin("foveal") + " log plot " + dir.path("bad.csv") + " -o " + dir.path("bad.png"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(dir.path("bad.csv") + ":10"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("left_dir_x"), std::string::npos) << r.err;
  test::write_file(dir.path("bad_trace.csv"),
                   "t_ns,left_state,left_x_px,left_y_px,left_confidence,right_state,right_x_px,right_y_px,right_confidence\n"
                   "0,fixation,1,2,1.00,fixation,1,2,1.00\n8000000,fixation,1,two,1.00,fixation,1,2,1.00\n");
  r = test::run(test::bin("foveal") + " log plot " + dir.path("bad_trace.csv") + " -o " + dir.path("bad.png"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(dir.path("bad_trace.csv") + ": line 3: column left_y_px"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("bad.png")));
}

}  // namespace
}  // namespace foveal

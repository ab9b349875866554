// `foveal record --control`: marks sent while recording (`foveal ctl mark`, with and
// without --socket) become marker rows of the log, and the end report's data quality is
// that of the log written (the same figures `foveal log quality` gives).
#include <gtest/gtest.h>

#include <filesystem>
#include <thread>

#include <nlohmann/json.hpp>

#include "test_support.hpp"

namespace foveal {
namespace {

bool wait_for(const std::function<bool()>& ready, int timeout_ms) {
  for (int waited = 0; waited < timeout_ms; waited += 20) {
    if (ready()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return ready();
}

TEST(RecordCli, MarksReachTheLogAndTheQualityIsReported) {
  test::TempDir d;
  const std::string env = "XDG_RUNTIME_DIR=" + d.path("run") + " ";
  const std::string log = d.path("rec.csv"), socket = d.path("run/foveal/record.sock");
  std::filesystem::create_directory(d.path("run"));
  std::filesystem::permissions(d.path("run"), std::filesystem::perms::owner_all);
  // 6 s: every call below must reach the recording while it runs; under ASan on a loaded
  // 2-core machine the five `foveal` starts before `pause` took longer than 2 s (CI).
  ASSERT_EQ(std::system((env + test::bin("foveal") + " record --source synthetic:5 --duration 6 --control --json --out " +
                         log + " >" + d.path("out.json") + " 2>" + d.path("err.txt") + " &")
                            .c_str()),
            0);
  ASSERT_TRUE(wait_for([&] { return std::filesystem::exists(socket); }, 5000)) << test::read_file(d.path("err.txt"));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));

  // Without --socket: to foveald (not running here) and to the recording.
  const auto first = test::run(env + test::bin("foveal") + " ctl mark trial 1, start");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const auto both = nlohmann::json::parse(first.out);
  EXPECT_EQ(both["record"]["ok"], true) << first.out;
  EXPECT_EQ(both["record"]["markers"], 1);
  EXPECT_EQ(both["foveald"]["ok"], false);
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  const auto second = test::run(test::bin("foveal") + " ctl --socket " + socket + " mark trial 1, end");
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_EQ(nlohmann::json::parse(second.out)["markers"], 2);
  // The recording's samples are waited for (up to 10 s), not counted against the clock.
  auto status = test::run(test::bin("foveal") + " ctl --json --socket " + socket + " status");
  for (int i = 0; i < 100 && status.exit_code == 0 && nlohmann::json::parse(status.out).value("samples", 0) <= 30; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    status = test::run(test::bin("foveal") + " ctl --json --socket " + socket + " status");
  }
  ASSERT_EQ(status.exit_code, 0) << status.err;
  EXPECT_GT(nlohmann::json::parse(status.out)["samples"].get<int>(), 30);
  const auto bad = test::run(test::bin("foveal") + " ctl --socket " + socket + " pause");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.out.find("a recording answers status and mark"), std::string::npos) << bad.out << bad.err;

  ASSERT_TRUE(wait_for([&] { return nlohmann::json::accept(test::read_file(d.path("out.json"))); }, 20000))
      << test::read_file(d.path("err.txt"));
  const auto j = nlohmann::json::parse(test::read_file(d.path("out.json")));
  EXPECT_EQ(j["markers"], 2);
  EXPECT_FALSE(std::filesystem::exists(socket));  // removed at the end

  // Two marker rows; the window between them has samples.
  const std::string text = test::read_file(log);
  EXPECT_NE(text.find("#mark,"), std::string::npos);
  EXPECT_NE(text.find(",trial 1, start\n"), std::string::npos);
  EXPECT_NE(text.find(",trial 1, end\n"), std::string::npos);
  const auto between = test::run(test::bin("foveal") + " log quality --json --between 'trial 1, start' 'trial 1, end' " + log);
  ASSERT_EQ(between.exit_code, 0) << between.err;
  const auto w = nlohmann::json::parse(between.out)["window"];
  // At least the 0.4 s slept between the marks (less a sample interval), within the recording.
  EXPECT_GE(w["duration_s"].get<double>(), 0.38);
  EXPECT_LT(w["duration_s"].get<double>(), 6.0);

  // The end report is the log's quality.
  const auto whole = test::run(test::bin("foveal") + " log quality --json " + log);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const auto q = nlohmann::json::parse(whole.out);
  ASSERT_TRUE(j["quality"].contains("channels")) << j["quality"].dump();
  for (const char* eye : {"left", "right", "binocular"})
    for (const char* k : {"rms_s2s_deg", "std_deg", "bcea_deg2", "data_loss_pct", "effective_frequency_hz"})
      EXPECT_EQ(j["quality"]["channels"][eye][k], q["channels"][eye][k]) << eye << " " << k;
  EXPECT_GT(j["quality"]["channels"]["left"]["rms_s2s_deg"].get<double>(), 0);
}

TEST(RecordCli, ControlSocketInAnOpenDirectoryIsRefused) {
  test::TempDir d;
  std::filesystem::create_directory(d.path("open"));
  std::filesystem::permissions(d.path("open"), std::filesystem::perms::all);
  const auto r = test::run(test::bin("foveal") + " record --source synthetic:5 --duration 1 --control-socket " +
                           d.path("open/r.sock") + " --out " + d.path("r.csv"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(d.path("open")), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(d.path("r.csv")));
}

}  // namespace
}  // namespace foveal

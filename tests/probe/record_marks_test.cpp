// `foveal record --control`: marks sent while recording (`foveal ctl mark`, with and
// without --socket) become marker rows of the log, and the end report's data quality is
// that of the log written (the same figures `foveal log quality` gives).
#include <gtest/gtest.h>

#include <signal.h>

#include <algorithm>
#include <filesystem>
#include <thread>

#include <nlohmann/json.hpp>

#include "test_support.hpp"

namespace foveal {
namespace {

/// A background `foveal record` that ends on SIGTERM; killed at scope exit if a failed
/// assertion left it running.
struct Recording {
  pid_t pid = -1;
  ~Recording() {
    if (pid > 0 && ::kill(pid, 0) == 0) ::kill(pid, SIGKILL);
  }
};

TEST(RecordCli, MarksReachTheLogAndTheQualityIsReported) {
  test::TempDir d;
  const std::string env = "XDG_RUNTIME_DIR=" + d.path("run") + " ";
  const std::string log = d.path("rec.csv"), socket = d.path("run/foveal/record.sock");
  std::filesystem::create_directory(d.path("run"));
  std::filesystem::permissions(d.path("run"), std::filesystem::perms::owner_all);
  // Ended by SIGTERM once every call below has reached it (CI once ran out of a fixed
  // 2 s recording under ASan); the 600 s duration is only a hang guard.
  ASSERT_EQ(std::system((env + test::bin("foveal") + " record --source synthetic:5 --duration 600 --control --json --out " +
                         log + " >" + d.path("out.json") + " 2>" + d.path("err.txt") + " & echo $! >" + d.path("pid"))
                            .c_str()),
            0);
  Recording rec;
  rec.pid = std::stoi(test::read_file(d.path("pid")));
  const auto status_of = [&] {
    const auto r = test::run(test::bin("foveal") + " ctl --json --socket " + socket + " status");
    return r.exit_code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json{{"samples", -1}};
  };
  ASSERT_TRUE(test::eventually([&] { return std::filesystem::exists(socket); })) << test::read_file(d.path("err.txt"));
  // The first mark comes after a sample: the window between the marks lies in the log.
  ASSERT_TRUE(test::eventually([&] { return status_of().value("samples", -1) > 0; })) << test::read_file(d.path("err.txt"));

  // Without --socket: to foveald (not running here) and to the recording.
  const auto first = test::run(env + test::bin("foveal") + " ctl mark trial 1, start");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const auto both = nlohmann::json::parse(first.out);
  EXPECT_EQ(both["record"]["ok"], true) << first.out;
  EXPECT_EQ(both["record"]["markers"], 1);
  EXPECT_EQ(both["foveald"]["ok"], false);
  const long long first_t_ns = both["record"]["t_ns"].get<long long>();
  // At least 0.4 s between the marks (load only lengthens it; the window is checked
  // against the marks' own stamps below).
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  const auto second = test::run(test::bin("foveal") + " ctl --socket " + socket + " mark trial 1, end");
  ASSERT_EQ(second.exit_code, 0) << second.err;
  const auto second_reply = nlohmann::json::parse(second.out);
  EXPECT_EQ(second_reply["markers"], 2);
  // Samples after the second mark are waited for, not counted against the clock.
  const int at_second = status_of().value("samples", -1);
  ASSERT_GT(at_second, 0);
  nlohmann::json status;
  ASSERT_TRUE(test::eventually([&] {
    status = status_of();
    return status.value("samples", -1) > std::max(30, at_second + 10);
  })) << status.dump();
  const auto bad = test::run(test::bin("foveal") + " ctl --socket " + socket + " pause");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.out.find("a recording answers status and mark"), std::string::npos) << bad.out << bad.err;

  ASSERT_EQ(::kill(rec.pid, SIGTERM), 0);
  ASSERT_TRUE(test::eventually([&] { return nlohmann::json::accept(test::read_file(d.path("out.json"))); }))
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
  // From mark to mark on the recording's clock: at least the 0.4 s slept between them.
  const double marks_s = static_cast<double>(second_reply["t_ns"].get<long long>() - first_t_ns) / 1e9;
  EXPECT_GE(w["duration_s"].get<double>(), 0.38);
  EXPECT_NEAR(w["duration_s"].get<double>(), marks_s, 1e-6);

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

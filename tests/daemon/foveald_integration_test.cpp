// foveald end to end: a real process, a real control socket, real signals.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>

#include "foveal/client.h"
#include "foveal/core/clock.hpp"
#include "foveal/runtime/control_server.hpp"
#include "foveal/runtime/fovea_shm_layout.h"
#include "test_support.hpp"

extern char** environ;

namespace foveal {
namespace {

class Foveald : public ::testing::Test {
 protected:
  void SetUp() override {
    std::filesystem::create_directories(dir_.path("config/foveal/profiles"));
    std::filesystem::create_directories(dir_.path("run"));
    test::write_file(dir_.path("config/foveal/profiles/bob.json"),
                     R"({"format":"foveal-profile v1","dominant_eye":"left","sigma_d":2.4,"sigma_nd":3.2})");
    socket_ = dir_.path("run/foveal/control.sock");
  }
  void TearDown() override {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }

  /// stderr_fd >= 0: foveald's stderr (and stdout to /dev/null); extra_env: VAR=VALUE.
  void start(std::vector<std::string> args, int stderr_fd = -1, const std::vector<std::string>& extra_env = {}) {
    std::vector<std::string> env_store = {"XDG_CONFIG_HOME=" + dir_.path("config"), "XDG_RUNTIME_DIR=" + dir_.path("run"),
                                          "PATH=/usr/bin:/bin"};
    env_store.insert(env_store.end(), extra_env.begin(), extra_env.end());
    args.insert(args.begin(), test::bin("foveald"));
    std::vector<char*> argv, envp;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    for (auto& e : env_store) envp.push_back(e.data());
    envp.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (stderr_fd >= 0) {
      posix_spawn_file_actions_adddup2(&actions, stderr_fd, STDERR_FILENO);
      posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    }
    const int spawned = ::posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    ASSERT_EQ(spawned, 0);
    // Ready once the control socket answers: its file appears at bind(), before listen(),
    // and a connect in between is refused (a loaded machine once ran a test there).
    bool ready = false;
    for (int i = 0; i < 6000 && !ready; ++i) {
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        break;
      }
      ready = std::filesystem::exists(socket_) && control_request(socket_, {{"cmd", "status"}}, 2000).ok();
      if (!ready) sleep_until_ns(monotonic_now_ns() + 10 * kNsPerMs);
    }
    ASSERT_TRUE(ready) << "foveald did not answer on its control socket";
  }
  nlohmann::json ctl(const nlohmann::json& req) {
    auto r = control_request(socket_, req);
    EXPECT_TRUE(r) << r.error().message;
    return r ? *r : nlohmann::json{};
  }
  /// Waits for the process; returns its exit code, or -1 if it is still running after `ms`.
  int wait_exit(int ms) {
    const int rc = test::wait_for_exit(pid_, ms);
    if (rc >= 0) pid_ = -1;
    return rc;
  }

  test::TempDir dir_;
  std::string socket_;
  pid_t pid_ = -1;
};

TEST_F(Foveald, StatusProfilesSettingsAndCleanSigterm) {
  // A small compositor at 60 Hz on a pattern: the frame stats show every settings change.
  start({"--loop", "--end", "5", "--speed", "1", "-q", "--no-shm", "--out", dir_.path("out"), "--scene",
         "pattern:checker", "--size", "64x36", "--fps", "60"});
  // Samples are waited for, not counted against the clock.
  nlohmann::json st;
  test::eventually([&] { return (st = ctl({{"cmd", "status"}})).value("samples", 0) > 10; }, test::kEventWithinMs, 10);
  EXPECT_EQ(st["ok"], true);
  EXPECT_EQ(st["state"], "running");
  EXPECT_GT(st["samples"].get<int>(), 10);
  EXPECT_EQ(st["profile"], "default");
  // Sample to publish in the gaze thread: well under a millisecond on a quiet machine
  // (printed, a figure); the bound is a hang guard, as a preempted thread may take a
  // scheduler's slice or more on a loaded machine.
  std::printf("gaze thread latency p99 %.3f ms\n", st["latency_ms"]["p99"].get<double>());
  EXPECT_LT(st["latency_ms"]["p99"].get<double>(), static_cast<double>(test::kReturnsWithinNs) / 1e6);

  auto used = ctl({{"cmd", "use"}, {"profile", "bob"}});
  EXPECT_EQ(used["profile"], "bob");
  EXPECT_EQ(used["settings"]["dominant_eye"], "left");
  EXPECT_DOUBLE_EQ(used["settings"]["sigma_nd"].get<double>(), 3.2);
  const int gen = used["settings"]["generation"].get<int>();
  EXPECT_EQ(used["applies_generation"].get<int>(), gen);
  // Status answers at once with the last completed frame: wait until the renderer has
  // applied a generation (the first frame with f auto also estimates f).
  const auto rendered_generation = [this](int g) {
    nlohmann::json r;
    test::eventually([&] { return (r = ctl({{"cmd", "status"}})["render"])["settings_generation"].get<int>() >= g; },
                     test::kEventWithinMs, 10);
    return r;
  };
  const nlohmann::json rendered = rendered_generation(gen);
  EXPECT_EQ(rendered["settings_generation"].get<int>(), gen);
  // Gaze to photon, live (docs/latency.md): frames with a sample have been shown by now.
  EXPECT_GT(rendered["gaze_to_photon"]["frames"].get<int>(), 0) << rendered.dump();
  EXPECT_GT(rendered["gaze_to_photon"]["gaze_to_photon_ms"]["p50"].get<double>(), 0.0);
  EXPECT_EQ(rendered["pacing"]["pacing"], "asap");

  auto set = ctl({{"cmd", "set"}, {"sigma_d", 2.8}, {"f_x", "auto"}});
  EXPECT_EQ(set["ok"], true);
  EXPECT_DOUBLE_EQ(set["settings"]["sigma_d"].get<double>(), 2.8);
  EXPECT_EQ(set["settings"]["f_x"], "auto");
  EXPECT_EQ(set["settings"]["generation"].get<int>(), gen + 1);
  EXPECT_EQ(set["applies_generation"].get<int>(), gen + 1);
  // The next frames render with the new pair: bob is left-dominant, so left 2.8, right 3.2.
  // Frames are waited for, not counted against the clock: a loaded machine renders fewer.
  auto frames = rendered_generation(gen + 1);
  test::eventually([&] { return (frames = ctl({{"cmd", "status"}})["render"])["frames"].get<int>() > 10; },
                   test::kEventWithinMs, 10);
  EXPECT_GT(frames["frames"].get<int>(), 10);
  EXPECT_EQ(frames["settings_generation"].get<int>(), gen + 1);
  EXPECT_DOUBLE_EQ(frames["last_frame"]["left"]["sigma"].get<double>(), 2.8);
  EXPECT_DOUBLE_EQ(frames["last_frame"]["right"]["sigma"].get<double>(), 3.2);
  EXPECT_EQ(frames["last_frame"]["left"]["buffer"][0].get<int>(), 11);  // round(32 / 2.8)

  auto bad = ctl({{"cmd", "set"}, {"sigma_nd", 1.5}});  // below sigma_d: refused, nothing changes
  EXPECT_EQ(bad["ok"], false);
  EXPECT_EQ(ctl({{"cmd", "status"}})["settings"]["generation"].get<int>(), gen + 1);
  EXPECT_EQ(ctl({{"cmd", "use"}, {"profile", "nobody"}})["ok"], false);
  EXPECT_EQ(ctl({{"cmd", "set"}, {"ipd_mm", 70}})["ok"], false);  // not a run-time setting

  auto fovea = ctl({{"cmd", "fovea"}});
  EXPECT_EQ(fovea["ok"], true);
  EXPECT_GE(fovea["left"]["x_px"].get<double>(), 0.0);
  EXPECT_LT(fovea["left"]["x_px"].get<double>(), 1440.0);

  EXPECT_EQ(ctl({{"cmd", "pause"}})["state"], "paused");
  EXPECT_EQ(ctl({{"cmd", "resume"}})["state"], "running");

  ASSERT_EQ(::kill(pid_, SIGTERM), 0);
  EXPECT_EQ(wait_exit(test::kExitsWithinMs), 0) << "foveald must exit 0 on SIGTERM";
  const auto summary = nlohmann::json::parse(test::read_file(dir_.path("out/summary.json")));
  EXPECT_EQ(summary["state"], "stopped");
  EXPECT_EQ(summary["profile"], "bob");
  EXPECT_FALSE(std::filesystem::exists(socket_)) << "the socket is removed on exit";
  // frames.csv holds the default pair (right-dominant: left 3.0), then bob's, then the change.
  const std::string csv = test::read_file(dir_.path("out/frames.csv"));
  EXPECT_NE(csv.find(",3.000,2.000,"), std::string::npos);
  EXPECT_NE(csv.find(",2.400,3.200,"), std::string::npos);
  EXPECT_NE(csv.find(",2.800,3.200,"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir_.path("out/frame_000000.png")));
}

TEST_F(Foveald, ABrokenProfileOnSighupKeepsTheLastGoodOne) {
  const int err = ::open(dir_.path("err.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  ASSERT_GE(err, 0);
  start({"--profile", "bob", "--loop", "--end", "5", "-q", "--no-shm", "--no-render", "--out", dir_.path("out")}, err);
  ::close(err);
  test::write_file(dir_.path("config/foveal/profiles/bob.json"), "{ \"sigma_d\": ");  // broken by hand
  ASSERT_EQ(::kill(pid_, SIGHUP), 0);
  // The reload's refusal is waited for (the line it logs), not a time.
  EXPECT_TRUE(test::eventually(
      [&] { return test::read_file(dir_.path("err.txt")).find("keeping the last good profile") != std::string::npos; }))
      << test::read_file(dir_.path("err.txt"));
  auto st = ctl({{"cmd", "status"}});
  EXPECT_EQ(st["state"], "running");
  EXPECT_DOUBLE_EQ(st["settings"]["sigma_d"].get<double>(), 2.4);
  ASSERT_EQ(::kill(pid_, SIGINT), 0);
  EXPECT_EQ(wait_exit(test::kExitsWithinMs), 0);
}

TEST_F(Foveald, AQualityTargetSetsTheLevelsItsTableChoosesUntilALevelIsSetByHand) {
  test::write_file(dir_.path("m.json"), test::read_file(test::source_path("data/display/htc_vive_pro_eye.json")));
  test::write_file(dir_.path("m.levels.json"), R"({"format": "foveal-jod-levels v1", "display": "htc_vive_pro_eye",
    "sigmas": [2, 3, 4], "f": [0.2, 0.4], "jod": [[9.5, 9.0, 8.5], [9.8, 9.4, 9.0]]})");
  // bob's pair 2.4 / 3.2 gives the EFR ratio 4/3.
  start({"--profile", "bob", "--quality", "jod:9.4", "--display", dir_.path("m.json"), "--loop", "--end", "5", "-q", "--no-shm",
         "--no-render", "--out", dir_.path("out")});
  auto st = ctl({{"cmd", "status"}})["settings"];
  EXPECT_NEAR(st["sigma_d"].get<double>(), 3.0, 1e-9);
  EXPECT_NEAR(st["sigma_nd"].get<double>(), 4.0, 1e-9);
  EXPECT_DOUBLE_EQ(st["f_x"].get<double>(), 0.4);
  auto set = ctl({{"cmd", "set"}, {"sigma_d", 2.2}});  // by hand: the target is off for this run
  ASSERT_EQ(set["ok"], true) << set.dump();
  EXPECT_DOUBLE_EQ(set["settings"]["sigma_d"].get<double>(), 2.2);
  EXPECT_DOUBLE_EQ(set["settings"]["sigma_nd"].get<double>(), 3.2);
  ASSERT_EQ(::kill(pid_, SIGINT), 0);
  EXPECT_EQ(wait_exit(test::kExitsWithinMs), 0);
  // A model without a table: foveald says so and does not start.
  test::write_file(dir_.path("bare.json"), test::read_file(dir_.path("m.json")));
  auto r = test::run("XDG_CONFIG_HOME=" + dir_.path("config") + " XDG_RUNTIME_DIR=" + dir_.path("run") + " " + test::bin("foveald") +
                     " --quality jod:9 --display " + dir_.path("bare.json") + " --no-render --no-shm --out " + dir_.path("out2"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bare.levels.json"), std::string::npos) << r.err;
}

TEST_F(Foveald, MarkersReachTheTraceInTimeOrder) {
  start({"--loop", "--end", "5", "--speed", "1", "-q", "--no-shm", "--no-render", "--out", dir_.path("out")});
  const auto samples_over = [this](int n) {
    return test::eventually([&] { return ctl({{"cmd", "status"}}).value("samples", 0) > n; }, test::kEventWithinMs, 10);
  };
  ASSERT_TRUE(samples_over(0));
  auto first = ctl({{"cmd", "mark"}, {"text", "trial 1, start"}});
  ASSERT_EQ(first["ok"], true) << first.dump();
  EXPECT_EQ(first["markers"], 1);
  ASSERT_TRUE(samples_over(20));  // samples between the marks, waited for
  // Through the command line, words joined by spaces.
  const auto cli = test::run("XDG_RUNTIME_DIR=" + dir_.path("run") + " " + test::bin("foveal") + " ctl mark trial 1 end");
  EXPECT_EQ(cli.exit_code, 0) << cli.err;
  EXPECT_NE(cli.out.find("\"markers\": 2"), std::string::npos) << cli.out;
  // Bad texts are refused and change nothing.
  EXPECT_EQ(ctl({{"cmd", "mark"}, {"text", "two\nlines"}})["ok"], false);
  EXPECT_EQ(ctl({{"cmd", "mark"}, {"text", ""}})["ok"], false);
  EXPECT_EQ(ctl({{"cmd", "mark"}, {"text", std::string(300, 'x')}})["ok"], false);
  EXPECT_EQ(ctl({{"cmd", "mark"}})["ok"], false);
  EXPECT_EQ(ctl({{"cmd", "status"}})["markers"], 2);
  auto last = ctl({{"cmd", "mark"}, {"text", "just before the end"}});
  ASSERT_EQ(::kill(pid_, SIGTERM), 0);
  ASSERT_EQ(wait_exit(test::kExitsWithinMs), 0);

  // Each marker is its own row, between the samples around its time; the rest of the
  // trace is sample rows as before.
  std::istringstream in(test::read_file(dir_.path("out/trace.csv")));
  std::string line;
  std::getline(in, line);  // the column row
  std::vector<std::string> marks;
  std::vector<long long> mark_t;
  long long prev_t = -1, samples = 0;
  while (std::getline(in, line)) {
    const bool mark = line.rfind("#mark,", 0) == 0;
    const std::string rest = mark ? line.substr(6) : line;
    const long long t = std::stoll(rest.substr(0, rest.find(',')));
    EXPECT_GE(t, prev_t) << line;
    prev_t = t;
    if (mark) {
      marks.push_back(rest.substr(rest.find(',') + 1));
      mark_t.push_back(t);
    } else {
      ++samples;
    }
  }
  EXPECT_GT(samples, 20);
  EXPECT_EQ(marks, (std::vector<std::string>{"trial 1, start", "trial 1 end", "just before the end"}));
  // Mark to mark on the trace's time base is mark to mark on the daemon's clock.
  ASSERT_EQ(mark_t.size(), 3u);
  EXPECT_EQ(mark_t[2] - mark_t[0], last["t_ns"].get<long long>() - first["t_ns"].get<long long>());
}

TEST_F(Foveald, MalformedAndOversizedSocketMessagesDoNotStopIt) {
  start({"--loop", "--end", "5", "-q", "--no-shm", "--no-render", "--out", dir_.path("out")});
  auto r = control_request(socket_, nlohmann::json::array({1, 2}));  // not an object
  ASSERT_TRUE(r);
  EXPECT_EQ((*r)["ok"], false);
  r = control_request(socket_, {{"cmd", std::string(70000, 'x')}});  // oversized line
  ASSERT_TRUE(r);
  EXPECT_EQ((*r)["ok"], false);
  EXPECT_EQ(ctl({{"cmd", "status"}})["control"]["bad_requests"].get<int>(), 2);
  ASSERT_EQ(::kill(pid_, SIGTERM), 0);
  EXPECT_EQ(wait_exit(test::kExitsWithinMs), 0);
}

/// Runs foveald to completion with the test's environment; stdout and stderr captured.
test::RunResult run_foveald(const std::string& dir, const std::string& args) {
  return test::run("env XDG_CONFIG_HOME=" + dir + "/config XDG_RUNTIME_DIR=" + dir + "/run " + test::bin("foveald") + " " +
                   args);
}

TEST_F(Foveald, SyntheticSourceForTwoSeconds) {
  const auto r = run_foveald(dir_.path(""), "--source synthetic --duration 2 --no-render --json --no-shm --out " + dir_.path("out"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  // 120 Hz in real time: the samples' stamps are 1/120 s apart on the runtime clock, and
  // none came before its time. (Not a count in 2 s of wall clock: a loaded machine
  // starts the source late and notices the end late.)
  std::istringstream trace(test::read_file(dir_.path("out/trace.csv")));
  std::string line;
  std::getline(trace, line);  // the column row
  std::vector<long long> t;
  while (std::getline(trace, line)) t.push_back(std::stoll(line.substr(0, line.find(','))));
  ASSERT_GT(t.size(), 10u);
  EXPECT_EQ(j["samples"].get<std::size_t>(), t.size());
  const double span_s = static_cast<double>(t.back() - t.front()) / 1e9;
  EXPECT_NEAR(static_cast<double>(t.size() - 1) / span_s, 120.0, 0.5);
  EXPECT_LE(static_cast<double>(t.size()), 120.0 * j["uptime_s"].get<double>() + 2) << "samples ahead of their time";
  EXPECT_EQ(j["source"]["driver"], "synthetic");
  EXPECT_EQ(j["source"]["device"]["driver"], "synthetic");
  EXPECT_GE(j["uptime_s"].get<double>(), 2.0);
}

TEST_F(Foveald, ReplaySpecIsWhatReplayDoes) {
  const std::string log = test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv");
  const std::string common = " --speed 0 --end 2 --no-render --no-control --no-shm -q --out ";
  const auto a = run_foveald(dir_.path(""), "--replay " + log + common + dir_.path("a"));
  const auto b = run_foveald(dir_.path(""), "--source replay:" + log + common + dir_.path("b"));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  // The same samples, filtered the same way; only the runtime clock differs.
  const auto without_time = [](const std::string& csv) {
    std::string out;
    std::istringstream in(csv);
    for (std::string line; std::getline(in, line);) out += line.substr(line.find(',') + 1) + "\n";
    return out;
  };
  const std::string ta = test::read_file(dir_.path("a/trace.csv")), tb = test::read_file(dir_.path("b/trace.csv"));
  EXPECT_GT(std::count(ta.begin(), ta.end(), '\n'), 200);
  EXPECT_EQ(without_time(ta), without_time(tb));
  const auto sa = nlohmann::json::parse(test::read_file(dir_.path("a/summary.json")));
  EXPECT_EQ(sa["source"]["spec"], "replay:" + log);
  EXPECT_EQ(sa["state"], "ended");
}

TEST_F(Foveald, BadSourceSpecsAreNamed) {
  auto r = run_foveald(dir_.path(""), "--source bogus --no-render --out " + dir_.path("out"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown source 'bogus'"), std::string::npos) << r.err;
  r = run_foveald(dir_.path(""), "--source synthetic --replay x.csv --no-render --out " + dir_.path("out"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("give one"), std::string::npos) << r.err;
  r = run_foveald(dir_.path(""), "--source replay:/nonexistent.csv --no-render --out " + dir_.path("out"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("/nonexistent.csv"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir_.path("out/summary.json")));
}

TEST_F(Foveald, HeadsetPoseSourceWaitsForItsHeadsetAndBadHeadSpecsAreNamed) {
  // No headset here: foveald runs, the camera stays at the scene's view, the state says so.
  const auto r = run_foveald(dir_.path(""), "--source synthetic --duration 1 --head auto --no-render --no-control --no-shm -q --out " +
                                                dir_.path("out"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(test::read_file(dir_.path("out/summary.json")));
  EXPECT_EQ(j["head"]["mode"], "auto");
  EXPECT_EQ(j["head"]["state"], "waiting") << j["head"].dump();
  EXPECT_EQ(j["head"]["poses"], 0);
  EXPECT_TRUE(j["head"].contains("prediction"));
  auto bad = run_foveald(dir_.path(""), "--source synthetic --head oculus --no-render --out " + dir_.path("bad"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("unknown head-pose source 'oculus'"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir_.path("bad/summary.json")));
}

#ifdef FOVEAL_TEST_HAVE_HID
TEST_F(Foveald, ALiveSourceWaitsForItsDevice) {
  // No such tracker: foveald keeps running, answers, and says what it waits for.
  start({"--source", "hid:/dev/hidraw-foveal-test", "--no-render", "--no-shm", "-q", "--out", dir_.path("out")});
  nlohmann::json st;
  test::eventually([&] { return (st = ctl({{"cmd", "status"}}))["source"].value("waiting_for", "") != ""; }, test::kEventWithinMs, 10);
  EXPECT_EQ(st["state"], "waiting");
  EXPECT_EQ(st["source"]["state"], "waiting");
  EXPECT_EQ(st["source"]["live"], true);
  EXPECT_NE(st["source"].value("waiting_for", "").find("hidraw-foveal-test"), std::string::npos) << st.dump();
  ASSERT_EQ(::kill(pid_, SIGTERM), 0);
  EXPECT_EQ(wait_exit(test::kExitsWithinMs), 0);
  const auto summary = nlohmann::json::parse(test::read_file(dir_.path("out/summary.json")));
  EXPECT_EQ(summary["samples"], 0);
}
#endif

// Frames of about a second (2880x1600, full rendering on llvmpipe): the control thread
// still answers without waiting for a frame, and SIGTERM still ends foveald mid-frame
// with complete outputs (the time it took is printed: the 1 s target is a figure, not a
// bound a loaded machine can miss).
TEST_F(Foveald, SlowFramesNeverMakeItDeaf) {
  start({"--method", "full", "--loop", "--end", "20", "--no-shm", "-q", "--out", dir_.path("out")});
  // Wait for the first frame to be under way.
  ASSERT_TRUE(test::eventually([&] { return ctl({{"cmd", "status"}})["render"]["frames"].get<int>() >= 1; },
                               test::kEventWithinMs, 100));
  // 20 requests back to back: a control thread that waited for frames would answer each
  // after another frame, so every reply would show a new frame count. However slow a
  // loaded machine makes both threads, most replies come within one frame.
  std::set<int> frames_seen;
  for (int i = 0; i < 20; ++i) {
    auto r = control_request(socket_, {{"cmd", "status"}}, 10000);
    ASSERT_TRUE(r) << r.error().message;
    EXPECT_EQ((*r)["ok"], true);
    frames_seen.insert((*r)["render"]["frames"].get<int>());
  }
  const auto st = ctl({{"cmd", "status"}});
  EXPECT_GE(st["render"]["passes_ms_median"]["cpu_frame"].get<double>(), 500.0) << "frames should be slow here";
  EXPECT_LE(frames_seen.size(), 5u) << "status requests waited for frames: 20 replies saw " << frames_seen.size() << " frame counts";
  auto set = ctl({{"cmd", "set"}, {"sigma_d", 2.2}});
  EXPECT_EQ(set["ok"], true);
  EXPECT_EQ(set["applies_generation"], set["settings"]["generation"]);

  const TimeNs t0 = monotonic_now_ns();
  ASSERT_EQ(::kill(pid_, SIGTERM), 0);
  const int rc = wait_exit(test::kExitsWithinMs);
  const double exit_ms = static_cast<double>(monotonic_now_ns() - t0) / 1e6;
  EXPECT_EQ(rc, 0) << "SIGTERM must end foveald, even mid-frame";
  std::printf("SIGTERM mid-frame: foveald exited after %.0f ms (the target is 1 s; docs/daemon.md)\n", exit_ms);
  const auto summary = nlohmann::json::parse(test::read_file(dir_.path("out/summary.json")));
  EXPECT_EQ(summary["state"], "stopped");
  EXPECT_GE(summary["render"]["frames"].get<int>(), 1);
  const std::string csv = test::read_file(dir_.path("out/frames.csv"));
  EXPECT_EQ(static_cast<int>(std::count(csv.begin(), csv.end(), '\n')), summary["render"]["frames"].get<int>() + 1)
      << "one row per completed frame, plus the header";
  for (const auto& e : std::filesystem::directory_iterator(dir_.path("out")))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << "left behind: " << e.path();
  EXPECT_FALSE(std::filesystem::exists(socket_));
}

// 31 clients that flood requests and never read their replies: the control thread drops
// or starves them, a 32nd client's status still answers at once, and the render thread
// goes on at its pace (frames counted before and during the flood, in the same run).
TEST_F(Foveald, NonReadingClientsStallNeitherStatusNorFrames) {
  start({"--loop", "--end", "5", "--no-shm", "-q", "--out", dir_.path("out"), "--scene", "pattern:checker", "--size",
         "64x36", "--fps", "30"});
  const auto frames_now = [this] { return ctl({{"cmd", "status"}})["render"]["frames"].get<int>(); };
  sleep_until_ns(monotonic_now_ns() + 300 * kNsPerMs);
  const int f0 = frames_now();
  sleep_until_ns(monotonic_now_ns() + 1000 * kNsPerMs);
  const int quiet = frames_now() - f0;

  std::vector<int> flooders;
  const std::string request = "{\"cmd\":\"status\"}\n";
  const auto connect_one = [this] {
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
    sockaddr_un a{};
    a.sun_family = AF_UNIX;
    std::snprintf(a.sun_path, sizeof a.sun_path, "%s", socket_.c_str());
    EXPECT_EQ(::connect(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a), 0);
    return fd;
  };
  for (int i = 0; i < 31; ++i) flooders.push_back(connect_one());
  const int f1 = frames_now();
  std::vector<double> ms;
  const TimeNs until = monotonic_now_ns() + 1000 * kNsPerMs;
  while (monotonic_now_ns() < until) {
    for (int& fd : flooders) {
      for (int k = 0; k < 8; ++k)
        if (::send(fd, request.data(), request.size(), MSG_NOSIGNAL | MSG_DONTWAIT) < 0 && errno != EAGAIN) {
          ::close(fd);  // dropped by the server: a new flooder takes its place
          fd = connect_one();
          break;
        }
    }
    const TimeNs t0 = monotonic_now_ns();
    auto r = control_request(socket_, {{"cmd", "status"}}, 2000);
    ms.push_back(static_cast<double>(monotonic_now_ns() - t0) / 1e6);
    EXPECT_TRUE(r) << r.error().message;
  }
  const int flooded = frames_now() - f1;
  for (int fd : flooders) ::close(fd);
  std::sort(ms.begin(), ms.end());
  ASSERT_FALSE(ms.empty());
  // Bounds that only a waiting or starving loop misses (one that waited 100 ms on each
  // stuck client took 3.1 s a request; a render thread behind the control lock drew
  // nothing): a loaded machine slows both phases alike. The figures are printed.
  std::printf("status under the flood: p50 %.2f ms, p99 %.2f ms (%zu requests); frames %d before, %d during\n",
              ms[ms.size() / 2], ms[ms.size() * 99 / 100], ms.size(), quiet, flooded);
  EXPECT_LT(ms[ms.size() * 99 / 100], 1000.0) << "status p99 under the flood (" << ms.size() << " requests)";
  EXPECT_GT(quiet, 3) << "about 30 frames a second without the flood";
  EXPECT_GE(flooded, quiet / 4) << "frames during the flood: " << flooded << ", before: " << quiet;
  ASSERT_EQ(::kill(pid_, SIGTERM), 0);
  EXPECT_EQ(wait_exit(test::kExitsWithinMs), 0);
}

/// The shared block's heartbeat (CLOCK_MONOTONIC ns), read as any client would; -1
/// when the block cannot be mapped.
std::int64_t heartbeat_of(const std::string& shm_name) {
  const int fd = ::shm_open(shm_name.c_str(), O_RDONLY | O_CLOEXEC, 0);
  if (fd < 0) return -1;
  void* p = ::mmap(nullptr, FOVEAL_SHM_V3_SIZE, PROT_READ, MAP_SHARED, fd, 0);
  ::close(fd);
  if (p == MAP_FAILED) return -1;
  const auto* hb = reinterpret_cast<const std::int64_t*>(static_cast<const char*>(p) + FOVEAL_SHM_HEARTBEAT_OFFSET);
  const std::int64_t v = __atomic_load_n(hb, __ATOMIC_ACQUIRE);
  ::munmap(p, FOVEAL_SHM_V3_SIZE);
  return v;
}

// stderr on a pipe nobody reads, full before foveald starts: its control thread wrote
// its log lines there itself, so after 686 `set` requests the socket went deaf, the
// heartbeat stopped and SIGTERM went unheard; when the reader died, SIGPIPE killed it
// with nothing committed. Now lines queue (and drop, counted) in front of a thread of
// their own, and SIGPIPE is ignored.
TEST_F(Foveald, AFullStderrPipeSilencesNeitherSocketNorHeartbeatNorSigterm) {
  int fds[2];
  ASSERT_EQ(::pipe2(fds, O_CLOEXEC), 0);
  ASSERT_EQ(::fcntl(fds[1], F_SETFL, O_NONBLOCK), 0);
  const std::string fill(4096, 'x');
  std::size_t filled = 0;
  while (::write(fds[1], fill.data(), fill.size()) > 0) filled += fill.size();
  while (::write(fds[1], "x", 1) > 0) ++filled;  // the last bytes: writes of a page wait for a page
  ASSERT_EQ(errno, EAGAIN);
  ASSERT_EQ(::fcntl(fds[1], F_SETFL, 0), 0);  // foveald gets a blocking, full stderr
  ASSERT_GT(filled, 0u);
  const std::string shm = "/foveal-test-stderr-" + std::to_string(::getpid());
  start({"--loop", "--end", "5", "--speed", "1", "--no-render", "--out", dir_.path("out")}, fds[1],
        {"FOVEAL_SHM_NAME=" + shm});
  ::close(fds[1]);

  // Each change logs an info line: changes are sent until the queue (256 KiB) has
  // dropped some, whatever the lines' length (at most 30000).
  for (int i = 0; i < 30000; ++i) {
    auto r = control_request(socket_, {{"cmd", "set"}, {"sigma_d", i % 2 ? 2.1 : 2.0}}, 10000);
    ASSERT_TRUE(r) << "set " << i + 1 << ": " << r.error().message;
    ASSERT_EQ((*r)["ok"], true) << r->dump();
    if (i % 500 == 499) {
      auto st = control_request(socket_, {{"cmd", "status"}}, 10000);
      ASSERT_TRUE(st) << st.error().message;
      if ((*st)["log"].value("dropped_lines", 0) > 0) break;
    }
  }
  nlohmann::json st;
  for (int i = 0; i < 10; ++i) {
    const TimeNs t0 = monotonic_now_ns();
    // Answered at all while stderr is stuck: a control thread that wrote its log lines
    // to the pipe itself would never reply.
    auto r = control_request(socket_, {{"cmd", "status"}}, 10000);
    const TimeNs took = monotonic_now_ns() - t0;
    ASSERT_TRUE(r) << r.error().message;
    if (i == 9) std::printf("status with stderr stuck: %.1f ms\n", static_cast<double>(took) / 1e6);
    st = *r;
  }
  EXPECT_EQ(st["state"], "running");
  EXPECT_GT(st["log"]["dropped_lines"].get<int>(), 0) << st["log"].dump();
  // The heartbeat goes on (every 10 ms): it is seen advancing.
  const std::int64_t h0 = heartbeat_of(shm);
  ASSERT_GT(h0, 0) << "cannot map " << shm;
  const bool beating = test::eventually([&] { return heartbeat_of(shm) > h0; });
  EXPECT_TRUE(beating) << "the shared block's heartbeat stopped";

  // The reader dies: the next lines are EPIPE, not SIGPIPE.
  ::close(fds[0]);
  for (int i = 0; i < 20; ++i) EXPECT_TRUE(control_request(socket_, {{"cmd", "set"}, {"sigma_d", 2.2}}, 10000));
  const TimeNs t0 = monotonic_now_ns();
  ASSERT_EQ(::kill(pid_, SIGTERM), 0);
  const int rc = wait_exit(test::kExitsWithinMs);
  EXPECT_EQ(rc, 0) << "exit code (128 + 13: killed by SIGPIPE)";
  std::printf("SIGTERM with stderr's reader gone: exited after %.0f ms\n", static_cast<double>(monotonic_now_ns() - t0) / 1e6);
  const auto summary = nlohmann::json::parse(test::read_file(dir_.path("out/summary.json")));
  EXPECT_EQ(summary["state"], "stopped");
  EXPECT_GT(summary["log"]["dropped_lines"].get<int>(), 0);
  EXPECT_GT(summary["samples"].get<int>(), 0);
  EXPECT_NE(test::read_file(dir_.path("out/trace.csv")).find('\n'), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(socket_)) << "the socket is removed on exit";
  EXPECT_EQ(heartbeat_of(shm), -1) << "the shared block is removed on exit";
  ::shm_unlink(shm.c_str());
}

// A stopped foveald (SIGSTOP) whose listen backlog is full: `foveal ctl --timeout-ms
// 100` and foveal_client_mark(..., 100, ...) blocked in connect() until killed.
TEST_F(Foveald, AStoppedFovealdWithAFullBacklogTimesClientsOut) {
  start({"--loop", "--end", "5", "-q", "--no-shm", "--no-render", "--out", dir_.path("out")});
  ASSERT_EQ(::kill(pid_, SIGSTOP), 0);
  // Filled before a thread still inside accept() stops, the backlog would gain a slot.
  ASSERT_TRUE(test::wait_until_stopped(pid_, test::kEventWithinMs)) << "foveald did not stop";
  std::vector<int> queued;  // connections it will never accept while stopped
  sockaddr_un a{};
  a.sun_family = AF_UNIX;
  std::snprintf(a.sun_path, sizeof a.sun_path, "%s", socket_.c_str());
  for (int i = 0; i < 10000; ++i) {
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
    if (::connect(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) {
      ASSERT_EQ(errno, EAGAIN) << std::strerror(errno);
      ::close(fd);
      break;
    }
    queued.push_back(fd);
  }
  ASSERT_LT(queued.size(), 10000u) << "the backlog never filled";
  const std::string ctl_status = "XDG_RUNTIME_DIR=" + dir_.path("run") + " timeout -s KILL 10 " + test::bin("foveal") +
                                 " ctl --timeout-ms 100 status";
  for (int i = 0; i < 100; ++i) {
    const TimeNs t0 = monotonic_now_ns();
    const auto r = test::run(ctl_status);
    const TimeNs took = monotonic_now_ns() - t0;
    ASSERT_NE(r.exit_code, 0);
    ASSERT_NE(r.err.find("not accepting connections within 100 ms"), std::string::npos) << r.err;
    ASSERT_LT(took, test::kReturnsWithinNs) << "foveal ctl call " << i + 1 << " took " << took / kNsPerMs << " ms";
  }
  for (int i = 0; i < 100; ++i) {
    foveal_error err{};
    const TimeNs t0 = monotonic_now_ns();
    ASSERT_EQ(foveal_client_mark(socket_.c_str(), "x", 100, nullptr, &err), FOVEAL_ERR_TIMEOUT) << err.message;
    const TimeNs took = monotonic_now_ns() - t0;
    ASSERT_LT(took, test::kReturnsWithinNs) << "foveal_client_mark call " << i + 1 << " took " << took / kNsPerMs << " ms";
  }
  for (int fd : queued) ::close(fd);
  ASSERT_EQ(::kill(pid_, SIGCONT), 0);
  EXPECT_EQ(ctl({{"cmd", "status"}})["ok"], true) << "it answers again once it runs";
  ASSERT_EQ(::kill(pid_, SIGTERM), 0);
  EXPECT_EQ(wait_exit(test::kExitsWithinMs), 0);
}

// A FIFO as ~/.config/foveal/active: foveald waited in open() for a writer, with SIGTERM
// already masked. It now refuses at once, naming the file.
TEST_F(Foveald, AFifoAsTheActiveProfileFileIsRefusedNamed) {
  const std::string active = dir_.path("config/foveal/active");
  ASSERT_EQ(::mkfifo(active.c_str(), 0600), 0);
  const auto r = test::run("timeout -s KILL 10 env XDG_CONFIG_HOME=" + dir_.path("config") +
                           " XDG_RUNTIME_DIR=" + dir_.path("run") + " " + test::bin("foveald") +
                           " --source synthetic --duration 5 --no-render --no-shm --out " + dir_.path("out"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(active + ": the active-profile file is a FIFO"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir_.path("out/summary.json")));
  // With --profile the active file is not read: foveald runs, and SIGTERM ends it.
  start({"--profile", "bob", "--loop", "--end", "5", "-q", "--no-shm", "--no-render", "--out", dir_.path("out")});
  EXPECT_EQ(ctl({{"cmd", "status"}})["profile"], "bob");
  ASSERT_EQ(::kill(pid_, SIGTERM), 0);
  EXPECT_EQ(wait_exit(test::kExitsWithinMs), 0);
}

}  // namespace
}  // namespace foveal

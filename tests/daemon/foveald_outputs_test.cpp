// foveald's outputs as a real process sees them: a stdout and stderr nobody reads, output
// targets that cannot be written, and what it shows before there is any gaze.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <filesystem>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/core/clock.hpp"
#include "foveal/runtime/control_server.hpp"
#include "test_support.hpp"

extern char** environ;

namespace foveal {
namespace {

class FovealdOutputs : public ::testing::Test {
 protected:
  void SetUp() override {
    std::filesystem::create_directories(dir_.path("config"));
    std::filesystem::create_directories(dir_.path("run"));
    socket_ = dir_.path("run/foveal/control.sock");
  }
  void TearDown() override {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  std::string env() const {
    return "XDG_CONFIG_HOME=" + dir_.path("config") + " XDG_RUNTIME_DIR=" + dir_.path("run") +
           " XDG_STATE_HOME=" + dir_.path("state") + " ";
  }
  /// foveald with `out_fd` as both its stdout and its stderr (-1: this process's).
  void spawn(std::vector<std::string> args, int out_fd) {
    std::vector<std::string> env_store = {"XDG_CONFIG_HOME=" + dir_.path("config"), "XDG_RUNTIME_DIR=" + dir_.path("run"),
                                          "XDG_STATE_HOME=" + dir_.path("state"), "PATH=/usr/bin:/bin"};
    args.insert(args.begin(), test::bin("foveald"));
    std::vector<char*> argv, envp;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    for (auto& e : env_store) envp.push_back(e.data());
    envp.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (out_fd >= 0) {
      posix_spawn_file_actions_adddup2(&actions, out_fd, STDOUT_FILENO);
      posix_spawn_file_actions_adddup2(&actions, out_fd, STDERR_FILENO);
    }
    const int spawned = ::posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    ASSERT_EQ(spawned, 0);
  }
  /// Waits (on a loaded machine, up to 60 s) until `status` says `ready`.
  nlohmann::json wait_status(const std::function<bool(const nlohmann::json&)>& ready) {
    nlohmann::json st;
    for (int i = 0; i < 6000; ++i) {
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        ADD_FAILURE() << "foveald exited before it was ready";
        return st;
      }
      if (auto r = control_request(socket_, {{"cmd", "status"}}, 2000); r && ready(*r)) return *r;
      sleep_until_ns(monotonic_now_ns() + 10 * kNsPerMs);
    }
    ADD_FAILURE() << "foveald never became ready";
    return st;
  }

  test::TempDir dir_;
  std::string socket_;
  pid_t pid_ = -1;
};

/// A pipe full before anyone writes to it; [0] is kept open and never read.
std::array<int, 2> full_pipe() {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) return {-1, -1};
  ::fcntl(fds[1], F_SETFL, O_NONBLOCK);
  const std::string page(4096, 'x');
  while (::write(fds[1], page.data(), page.size()) > 0) {
  }
  while (::write(fds[1], "x", 1) > 0) {  // the last bytes: writes of a page wait for a page
  }
  ::fcntl(fds[1], F_SETFL, 0);  // foveald gets a blocking, full pipe, as a shell's `|` gives
  return {fds[0], fds[1]};
}

// `foveald 2>&1 | reader-that-never-reads`: SIGTERM stopped it but it never exited (20 s
// and more), its log writer blocked in write() on stderr and its main thread in the
// exit-time flush of stdout. Now no write of any thread waits for the reader: it exits 0
// with everything committed.
TEST_F(FovealdOutputs, SigtermEndsItWhenStdoutAndStderrAreAPipeNobodyReads) {
  const auto pipe = full_pipe();
  ASSERT_GE(pipe[1], 0);
  // Info lines, a rendering compositor (Mesa writes to stderr too) and a gaze thread.
  spawn({"--source", "synthetic", "--no-shm", "--scene", "pattern:checker", "--size", "64x36", "--fps", "30", "--out",
         dir_.path("out")},
        pipe[1]);
  ::close(pipe[1]);
  wait_status([](const nlohmann::json& st) {
    return st.value("samples", 0) > 0 && st["render"].is_object() && st["render"].value("frames", 0) > 1;
  });
  ASSERT_GT(pid_, 0);
  const TimeNs t0 = monotonic_now_ns();
  ASSERT_EQ(::kill(pid_, SIGTERM), 0);
  // 20 s only guards the test against a foveald that never exits; it is not what is checked.
  const int rc = test::wait_for_exit(pid_, 20000);
  const double took_s = static_cast<double>(monotonic_now_ns() - t0) / 1e9;
  if (rc >= 0) pid_ = -1;
  ::close(pipe[0]);
  ASSERT_EQ(rc, 0) << "foveald did not exit after SIGTERM (-1: still running after 20 s)";
  RecordProperty("sigterm_to_exit_ms", static_cast<int>(took_s * 1000));
  const auto summary = nlohmann::json::parse(test::read_file(dir_.path("out/summary.json")));
  EXPECT_EQ(summary["state"], "stopped");
  EXPECT_GT(summary["samples"].get<int>(), 0);
  EXPECT_TRUE(summary["log"].contains("dropped_lines"));
  EXPECT_NE(test::read_file(dir_.path("out/trace.csv")).find('\n'), std::string::npos);
  EXPECT_NE(test::read_file(dir_.path("out/frames.csv")).find('\n'), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(socket_)) << "the socket is removed on exit";
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// A symbolic link planted at the first PNG's name: rendering began, then the session
// ended without summary.json or frames.csv, the message printed twice. Now it is refused
// before any work, once.
TEST_F(FovealdOutputs, APngTargetThatIsASymlinkIsRefusedBeforeAnyWork) {
  const std::string out = dir_.path("out");
  std::filesystem::create_directories(out);
  std::filesystem::create_symlink(dir_.path("elsewhere.png"), out + "/frame_000000.png");
  const auto r = test::run(env() + test::bin("foveald") +
                           " --source synthetic --no-shm --no-control --frames 2 --size 64x36 --scene pattern:checker"
                           " --out " + out);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(count(r.err, out + "/frame_000000.png: is a symbolic link"), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out + "/trace.csv")) << "work began";
  EXPECT_FALSE(std::filesystem::exists(dir_.path("elsewhere.png")));
  EXPECT_TRUE(std::filesystem::is_symlink(out + "/frame_000000.png"));
}

// With --frames the last frame's name is known too.
TEST_F(FovealdOutputs, TheLastPngTargetIsCheckedWhenFramesIsGiven) {
  const std::string out = dir_.path("out");
  std::filesystem::create_directories(out + "/frame_000002.png");  // a directory
  const auto r = test::run(env() + test::bin("foveald") +
                           " --source synthetic --no-shm --no-control --frames 3 --size 64x36 --scene pattern:checker"
                           " --out " + out);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(count(r.err, out + "/frame_000002.png: is a directory"), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out + "/trace.csv")) << "work began";
}

// A PNG whose name is not known up front (every K-th frame of an open-ended session)
// that cannot be written ends the session, but with its summary and frames.csv, and
// the message once.
TEST_F(FovealdOutputs, APngThatCannotBeSavedMidRunEndsTheSessionWithItsSummary) {
  const std::string out = dir_.path("out");
  std::filesystem::create_directories(out);
  std::filesystem::create_symlink(dir_.path("elsewhere.png"), out + "/frame_000001.png");
  const auto r = test::run(env() + test::bin("foveald") +
                           " --source synthetic --duration 120 --no-shm --no-control --save-every 1 --size 64x36"
                           " --scene pattern:checker --out " + out);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(count(r.err, out + "/frame_000001.png: is a symbolic link"), 1) << r.err;
  ASSERT_TRUE(std::filesystem::exists(out + "/summary.json")) << r.err;
  const auto summary = nlohmann::json::parse(test::read_file(out + "/summary.json"));
  EXPECT_EQ(summary["render"]["frames"].get<int>(), 2);
  EXPECT_NE(test::read_file(out + "/frames.csv").find('\n'), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(out + "/frame_000000.png"));
  EXPECT_FALSE(std::filesystem::exists(dir_.path("elsewhere.png")));
}

/// frames.csv's rows as name -> value per row.
std::vector<std::map<std::string, std::string>> csv_rows(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::vector<std::string> names;
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ls(line);
    for (std::string c; std::getline(ls, c, ',');) cells.push_back(c);
    if (names.empty()) {
      names = cells;
      continue;
    }
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < cells.size() && i < names.size(); ++i) row[names[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}

// No tracker yet (`--source auto` with no device: it waits): every frame was rendered
// with the fovea at (0, 0), the top-left corner. Before the first sample the fovea is
// the optical centre.
TEST_F(FovealdOutputs, BeforeTheFirstSampleFramesAreFoveatedAtTheCentre) {
  const std::string out = dir_.path("out");
  const auto r = test::run(env() + test::bin("foveald") +
                           " --source auto --no-shm --no-control --frames 2 --size 320x180 --scene pattern:checker"
                           " --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = csv_rows(test::read_file(out + "/frames.csv"));
  ASSERT_EQ(rows.size(), 2u);
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("t_ns"), "0") << "no sample was shown";
    for (const char* c : {"fovea_left_x", "fovea_left_y", "fovea_right_x", "fovea_right_y"})
      EXPECT_NEAR(std::stod(row.at(c)), 0.5, 0.01) << c;
  }
}

TEST_F(FovealdOutputs, BeforeTheFirstSampleCtlFoveaSaysTheCentre) {
  spawn({"--source", "auto", "--no-shm", "--no-render", "-q", "--out", dir_.path("out")}, -1);
  const auto st = wait_status([](const nlohmann::json& s) { return s.contains("state"); });
  EXPECT_EQ(st["source"]["state"], "waiting");
  auto f = control_request(socket_, {{"cmd", "fovea"}}, 2000);
  ASSERT_TRUE(f) << f.error().message;
  // The Vive Pro Eye's eye, 1440x1600 (the default display model).
  for (const char* eye : {"left", "right"}) {
    EXPECT_FLOAT_EQ((*f)[eye]["x_px"].get<float>(), 720.0f) << f->dump();
    EXPECT_FLOAT_EQ((*f)[eye]["y_px"].get<float>(), 800.0f) << f->dump();
    EXPECT_EQ((*f)[eye]["state"], "lost");
  }
  ASSERT_EQ(::kill(pid_, SIGTERM), 0);
  EXPECT_EQ(test::wait_for_exit(pid_, 20000), 0);
  pid_ = -1;
}

// `foveal ctl` prints one line a person reads (the whole record with --json), says in
// which pixel space the fovea is, and that a live change is not saved.
TEST_F(FovealdOutputs, CtlPrintsOneLineSummariesAndTheWholeRecordWithJson) {
  spawn({"--source", "auto", "--no-shm", "--no-render", "-q", "--out", dir_.path("out")}, -1);
  const auto st = wait_status([](const nlohmann::json& s) { return s.contains("state"); });
  const std::string ctl = env() + test::bin("foveal") + " ctl ";
  const auto line = test::run(ctl + "status");
  ASSERT_EQ(line.exit_code, 0) << line.err;
  EXPECT_EQ(std::count(line.out.begin(), line.out.end(), '\n'), 1) << line.out;
  for (const std::string& part : std::vector<std::string>{st["state"].get<std::string>() + " · source auto waiting",
                                                          "profile default: right dominant, sigma 2/3", "no rendering", " · up "})
    EXPECT_NE(line.out.find(part), std::string::npos) << part << " not in: " << line.out;
  const auto whole = test::run(ctl + "--json status");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_EQ(nlohmann::json::parse(whole.out)["profile"], "default");
  const auto fovea = test::run(ctl + "fovea");
  ASSERT_EQ(fovea.exit_code, 0) << fovea.err;
  EXPECT_NE(fovea.out.find("left 720.0,800.0 (lost), right 720.0,800.0 (lost) · pixels of one eye's 1440x1600 viewport, origin top-left"),
            std::string::npos) << fovea.out;
  const auto set = test::run(ctl + "set sigma_d=2.5 sigma_nd=3.5");
  ASSERT_EQ(set.exit_code, 0) << set.err;
  EXPECT_NE(set.out.find("sigma 2.5/3.5 · not saved"), std::string::npos) << set.out;
  ASSERT_EQ(::kill(pid_, SIGTERM), 0);
  EXPECT_EQ(test::wait_for_exit(pid_, 20000), 0);
  pid_ = -1;
}

// The user service (`foveald --service`, the unit's command line): with no tracker and no
// headset it waits for them, renders nothing, writes under $XDG_STATE_HOME/foveal, and
// stops cleanly on SIGTERM; options come from foveald.conf, the command line winning.
TEST_F(FovealdOutputs, TheServiceWaitsForTheTrackerWithoutRenderingAndStopsOnSigterm) {
  spawn({"--service", "--no-shm", "-q"}, -1);
  const auto st = wait_status([](const nlohmann::json& s) { return s.contains("state"); });
  EXPECT_EQ(st["source"]["state"], "waiting") << st.dump();
  EXPECT_FALSE(st.contains("render") && st["render"].is_object() && st["render"].value("frames", 0) > 0) << st.dump();
  ASSERT_EQ(::kill(pid_, SIGTERM), 0);
  EXPECT_EQ(test::wait_for_exit(pid_, 20000), 0);
  pid_ = -1;
  const auto summary = nlohmann::json::parse(test::read_file(dir_.path("state/foveal/summary.json")));
  EXPECT_EQ(summary["state"], "stopped");
  EXPECT_EQ(summary["samples"].get<int>(), 0);
  // No trace: a service runs for days, and trace.csv is held until exit.
  EXPECT_TRUE(summary["trace"].is_null()) << summary.dump();
  EXPECT_FALSE(std::filesystem::exists(dir_.path("state/foveal/trace.csv")));
}

TEST_F(FovealdOutputs, TheServiceTakesItsOptionsFileAndTheCommandLineWins) {
  std::filesystem::create_directories(dir_.path("config/foveal"));
  test::write_file(dir_.path("config/foveal/foveald.conf"),
                   "# the user's service\nquality = jod:9.5\n\nlatch = early\npredict = off\n");
  const auto r = test::run(env() + test::bin("foveald") + " --service --latch late --print-config");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* line : {"source = auto\n", "head = auto\n", "render = off\n", "trace = off\n", "quality = jod:9.5\n",
                           "latch = late\n", "predict = off\n"})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << " missing from:\n" << r.out;
  EXPECT_NE(r.out.find("out = " + dir_.path("state") + "/foveal\n"), std::string::npos) << r.out;
  // Without --service the file is read only when named, and nothing else changes.
  const auto plain = test::run(env() + test::bin("foveald") + " --print-config");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_NE(plain.out.find("# source\n"), std::string::npos) << plain.out;
  EXPECT_NE(plain.out.find("render = on\n"), std::string::npos) << plain.out;
  const auto named = test::run(env() + test::bin("foveald") + " --config " + dir_.path("config/foveal/foveald.conf") + " --print-config");
  ASSERT_EQ(named.exit_code, 0) << named.err;
  EXPECT_NE(named.out.find("latch = early\n"), std::string::npos) << named.out;
  EXPECT_NE(named.out.find("render = on\n"), std::string::npos) << named.out;
  EXPECT_NE(named.out.find("trace = on\n"), std::string::npos) << named.out;
  // The service traces when its file says so.
  test::write_file(dir_.path("config/foveal/foveald.conf"), "trace = on\n");
  const auto traced = test::run(env() + test::bin("foveald") + " --service --print-config");
  ASSERT_EQ(traced.exit_code, 0) << traced.err;
  EXPECT_NE(traced.out.find("trace = on\n"), std::string::npos) << traced.out;
}

TEST_F(FovealdOutputs, ABrokenOptionsFileIsRefusedNamingTheFileTheLineAndTheKey) {
  const std::string conf = dir_.path("broken.conf");
  struct Case {
    const char* text;
    const char* says;
  } cases[] = {{"source = auto\n\nsideways = 1\n", ":3: unknown key 'sideways'"},
               {"latch = sideways\n", "--latch"},
               {"render = maybe\n", "render: on or off"},
               {"quality = jod:9\nquality = jod:8\n", ":2: quality: given twice"},
               {"source auto\n", ":1: expected `key = value`"}};
  for (const Case& c : cases) {
    test::write_file(conf, c.text);
    const auto r = test::run(env() + test::bin("foveald") + " --service --config " + conf + " --print-config");
    EXPECT_EQ(r.exit_code, 2) << c.text;
    EXPECT_NE(r.err.find(conf), std::string::npos) << c.text << ": " << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.text << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

TEST_F(FovealdOutputs, FovealServiceSetsShowsAndUnsetsTheServicesOptions) {
  const std::string foveal = env() + test::bin("foveal");
  auto set = test::run(foveal + " service set quality jod:9.5");
  ASSERT_EQ(set.exit_code, 0) << set.err;
  ASSERT_EQ(test::run(foveal + " service set source hid").exit_code, 0);
  const auto shown = test::run(foveal + " service show --json");
  ASSERT_EQ(shown.exit_code, 0) << shown.err;
  const auto j = nlohmann::json::parse(shown.out);
  EXPECT_EQ(j["path"], dir_.path("config") + "/foveal/foveald.conf");
  EXPECT_EQ(j["entries"]["quality"], "jod:9.5");
  EXPECT_EQ(j["entries"]["source"], "hid");
  // What `set` wrote is what the service reads.
  const auto used = test::run(env() + test::bin("foveald") + " --service --print-config");
  ASSERT_EQ(used.exit_code, 0) << used.err;
  EXPECT_NE(used.out.find("source = hid\n"), std::string::npos) << used.out;
  const auto bad = test::run(foveal + " service set sideways 1");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("unknown key 'sideways'"), std::string::npos) << bad.err;
  ASSERT_EQ(test::run(foveal + " service unset source").exit_code, 0);
  const auto after = nlohmann::json::parse(test::run(foveal + " service show --json").out);
  EXPECT_FALSE(after["entries"].contains("source")) << after.dump();
  EXPECT_EQ(test::run(foveal + " service unset source").exit_code, 2) << "unsetting what is not set is an error";
}

}  // namespace
}  // namespace foveal

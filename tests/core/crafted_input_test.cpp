// Crafted data (docs/bad-input.md, "Crafted data"): JSON nested past the limit, FIFOs
// and directories as inputs, extreme timestamps and numbers. Each is a clear error,
// exit 2 from the CLI, never a crash or a hang.
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "foveal/core/display_model.hpp"
#include "foveal/core/gaze_log.hpp"
#include "foveal/core/json_file.hpp"
#include "foveal/core/pacer.hpp"
#include "foveal/core/read_file.hpp"
#include "foveal/drivers/replay_source.hpp"
#include "foveal/runtime/control_server.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

std::string nested(std::size_t depth) { return std::string(depth, '[') + std::string(depth, ']'); }

const std::string kHeader =
    "# foveal-gaze-log v1\n# rate_hz=120\n"
    "t_ns,left_valid,left_dir_x,left_dir_y,left_dir_z,left_origin_x_mm,left_origin_y_mm,left_origin_z_mm,left_pupil_mm,"
    "left_openness,right_valid,right_dir_x,right_dir_y,right_dir_z,right_origin_x_mm,right_origin_y_mm,right_origin_z_mm,"
    "right_pupil_mm,right_openness,combined_valid,combined_dir_x,combined_dir_y,combined_dir_z,combined_origin_x_mm,"
    "combined_origin_y_mm,combined_origin_z_mm\n";
std::string row(const std::string& t, const char* lx = "0.1") { return t + ",1," + lx + ",0,-0.99,,,,,,1,0.1,0,-0.99,,,,,,0,,,,,,\n"; }

// Runs the foveal CLI with a time limit (a blocked open would otherwise hang the test).
test::RunResult foveal_cli(const std::string& args, const std::string& env = "") {
  return test::run(env + " timeout -s KILL 20 " + test::bin("foveal") + " " + args);
}

TEST(JsonLimits, DepthIsCountedOnTheBytesAndStringsDoNotCount) {
  EXPECT_TRUE(parse_json(nested(64), "x"));
  auto deep = parse_json(nested(65), "f.json");
  ASSERT_FALSE(deep);
  EXPECT_EQ(deep.error().message, "f.json: JSON nested deeper than 64 levels (at byte 64)");
  EXPECT_TRUE(parse_json("{\"a\": \"" + std::string(1000, '[') + "\\\"[[\"}", "x"));  // brackets in a string
  EXPECT_FALSE(parse_json(nested(1000000), "x"));
  auto big = parse_json("[" + std::string(2 << 20, ' ') + "]", "big.json");
  ASSERT_FALSE(big);
  EXPECT_NE(big.error().message.find("big.json: JSON of 2097154 bytes, more than the 1 MiB accepted"), std::string::npos)
      << big.error().message;
  EXPECT_TRUE(parse_json_or_discarded(nested(65)).is_discarded());
  EXPECT_FALSE(parse_json_or_discarded("{\"cmd\": \"status\"}").is_discarded());
}

TEST(JsonLimits, AControlRequestNestedPastTheLimitGetsAnErrorReply) {
  test::TempDir d;
  auto server = ControlServer::listen(d.path("c.sock"));
  ASSERT_TRUE(server) << server.error().message;
  int handled = 0;
  const ControlServer::Handler handler = [&](const nlohmann::json&) -> nlohmann::json {
    ++handled;
    return {{"ok", true}};
  };
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::snprintf(addr.sun_path, sizeof addr.sun_path, "%s", server->path().c_str());
  ASSERT_EQ(::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr), 0);
  auto ask = [&](const std::string& line) {
    const std::string msg = line + "\n";
    EXPECT_EQ(::send(fd, msg.data(), msg.size(), MSG_NOSIGNAL), static_cast<ssize_t>(msg.size()));
    std::string reply;
    for (int i = 0; i < 200 && reply.find('\n') == std::string::npos; ++i) {
      server->poll(10, handler);
      char buf[4096];
      const ssize_t n = ::recv(fd, buf, sizeof buf, MSG_DONTWAIT);
      if (n > 0) reply.append(buf, static_cast<std::size_t>(n));
    }
    return reply;
  };
  // 30,000 deep fits one 64 KiB line; the handler (which copies the request) never sees it.
  const std::string deep = ask("{\"cmd\": \"set\", \"filter\": " + nested(30000) + "}");
  EXPECT_NE(deep.find("malformed request"), std::string::npos) << deep;
  EXPECT_EQ(handled, 0);
  EXPECT_NE(ask("{\"cmd\": \"status\"}").find("\"ok\":true"), std::string::npos);
  EXPECT_EQ(handled, 1);
  ::close(fd);
}

TEST(JsonLimits, DeepDisplayModelIsRefusedNamingTheFile) {
  test::TempDir d;
  // 500,000 deep fits the 1 MiB size limit (the depth limit answers); 10^6 deep does not.
  for (const auto& [depth, message] : {std::pair{500000u, "deep.json: JSON nested deeper than 64 levels"},
                                       std::pair{1000000u, "deep.json: display model is 2000010 bytes, more than the 1 MiB"}}) {
    test::write_file(d.path("deep.json"), "{\"name\": " + nested(depth) + "}");
    auto m = DisplayModel::load(d.path("deep.json"));
    ASSERT_FALSE(m);
    EXPECT_EQ(m.error().kind, ErrorKind::bad_input);
    EXPECT_NE(m.error().message.find(message), std::string::npos) << m.error().message;
  }
}

// Found by fuzz_display: a display model that is a JSON array, or whose format is not a
// string, aborted (uncaught type_error); numbers past int or float were cast with
// undefined behaviour.
TEST(DisplayModelBadInput, WrongKindsOfJsonAreErrorsNotCrashes) {
  test::TempDir d;
  for (const auto& [text, message] : {std::pair{"[]", "m.json: expected a JSON object"},
                                      std::pair{"5", "m.json: expected a JSON object"},
                                      std::pair{"{\"format\": 68038064520000000007791}", "m.json: field 'format' must be"},
                                      std::pair{"{\"eye_width\": 1e300}", "m.json: eye_width: expected an integer, got 1e+300"},
                                      std::pair{"{\"eye_width\": 99999999999}", "m.json: eye_width: 99999999999 is out of range"},
                                      std::pair{"{\"ipd_mm\": 1e300}", "m.json: ipd_mm: 1e+300 is out of range"},
                                      std::pair{"{\"left\": {\"tangents\": {\"left\": \"x\"}}}", "m.json: left: expected a number"}}) {
    SCOPED_TRACE(text);
    test::write_file(d.path("m.json"), text);
    auto m = DisplayModel::load(d.path("m.json"));
    ASSERT_FALSE(m);
    EXPECT_NE(m.error().message.find(message), std::string::npos) << m.error().message;
  }
}

TEST(JsonLimits, DeepProfileFilterExitsTwoInImportShowAndSet) {
  test::TempDir d;
  const std::string env = "XDG_CONFIG_HOME=" + d.path();
  ASSERT_EQ(foveal_cli("profile create alice", env).exit_code, 0);
  for (const auto& [depth, problem] : {std::pair{70000u, "JSON nested deeper than 64 levels"},
                                       std::pair{1000000u, "profile is 2000047 bytes, more than the 1 MiB foveal reads"}}) {
    SCOPED_TRACE(depth);
    const std::string file = d.path("deep.json");
    test::write_file(file, "{\"format\": 1, \"name\": \"bob\", \"filter\": {\"a\": " + nested(depth) + "}}");
    auto r = foveal_cli("profile import " + file + " --name bob", env);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("deep.json: " + std::string(problem)), std::string::npos) << r.err;
    // The same file put into the store by hand: show reports it.
    std::filesystem::copy_file(file, d.path("foveal/profiles/carol.json"), std::filesystem::copy_options::overwrite_existing);
    r = foveal_cli("profile show carol", env);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("carol.json: " + std::string(problem)), std::string::npos) << r.err;
  }
  // 30,000 deep: a longer argument would pass the kernel's 128 KiB limit for one argument.
  auto r = foveal_cli("profile set alice filter '{\"a\": " + nested(30000) + "}'", env);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("profile alice: filter: JSON nested deeper than 64 levels"), std::string::npos) << r.err;
  r = foveal_cli("profile set alice sigma_d 1e400", env);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("'1e400' is out of range"), std::string::npos) << r.err;
}

TEST(NonRegularInputs, AFifoWithNoWriterIsRefusedAtOnceByEveryReader) {
  test::TempDir d;
  const std::string fifo = d.path("fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string env = "XDG_CONFIG_HOME=" + d.path();
  for (const std::string& args : {"log validate " + fifo, "replay " + fifo, "import --from sranipal " + fifo + " --out " + d.path("o.csv"),
                                  "import --from pupil " + fifo + " --out " + d.path("o.csv"), "profile import " + fifo + " --name x",
                                  "calibrate --profile p --answers " + fifo + " --dry-run",
                                  "replay " + test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv") + " --config " + fifo}) {
    SCOPED_TRACE(args);
    auto r = foveal_cli(args, env);
    EXPECT_EQ(r.exit_code, 2) << r.err;  // 137 would be the timeout's SIGKILL
    EXPECT_NE(r.err.find("is a FIFO; foveal reads only regular files"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(d.path("o.csv")));
  }
  auto r = foveal_cli("log validate " + d.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("is a directory"), std::string::npos) << r.err;
}

TEST(NonRegularInputs, FovealdRefusesAFifoAsItsReplayLogAndExits) {
  test::TempDir d;
  const std::string fifo = d.path("fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  auto r = test::run("XDG_CONFIG_HOME=" + d.path() + " XDG_RUNTIME_DIR=" + d.path() + " timeout -s KILL 20 " + test::bin("foveald") +
                     " --replay " + fifo + " --no-render --out " + d.path("out"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("is a FIFO"), std::string::npos) << r.err;
}

TEST(HidDecodeInput, ADirectoryIsAnErrorNotHexText) {
  test::TempDir d;
  auto r = foveal_cli("hid decode --descriptor " + d.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--descriptor file is a directory"), std::string::npos) << r.err;
}

TEST(ExtremeTimes, Int64MinAndOtherOutOfRangeTimestampsAreRefused) {
  test::TempDir d;
  for (const std::string& t : {std::string("-9223372036854775808"), std::string("4611686018427387904"), std::string("-4611686018427387905")}) {
    SCOPED_TRACE(t);
    test::write_file(d.path("t.csv"), kHeader + row(t) + row("0"));
    auto r = foveal_cli("log validate " + d.path("t.csv"));
    EXPECT_EQ(r.exit_code, 2) << r.out;
    EXPECT_NE(r.err.find(":4: t_ns: " + t + " is out of range"), std::string::npos) << r.err;
  }
  test::write_file(d.path("t.csv"), kHeader + row("99999999999999999999"));
  auto r = foveal_cli("log validate " + d.path("t.csv"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("'99999999999999999999' is out of range"), std::string::npos) << r.err;
  // The limits themselves are fine, and so is their difference.
  test::write_file(d.path("t.csv"), kHeader + row("-4611686018427387904") + row("4611686018427387903"));
  r = foveal_cli("log validate " + d.path("t.csv") + " --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("9223372036.85"), std::string::npos) << r.out;  // the duration, unwrapped
}

TEST(ExtremeTimes, ReplayAndPacingSaturateInsteadOfWrapping) {
  // A slowed-down pacer past int64: the latest time there is, not a time in the past.
  Pacer slow(0.001);
  slow.start(-kMaxGazeLogTimeNs);
  EXPECT_EQ(slow.due(kMaxGazeLogTimeNs - 1), std::numeric_limits<TimeNs>::max());
  EXPECT_EQ(slow.due(-kMaxGazeLogTimeNs), slow.due(-kMaxGazeLogTimeNs));
  test::TempDir d;
  test::write_file(d.path("t.csv"), kHeader + row("-4611686018427387904") + row("4611686018427387903"));
  ReplayOptions o;
  o.path = d.path("t.csv");
  o.speed = 0;
  o.loop = true;
  ReplaySource src(o);
  ASSERT_TRUE(src.open());
  ASSERT_TRUE(src.start());
  ReadResult a = src.next(std::chrono::seconds(1)), b = src.next(std::chrono::seconds(1));
  ASSERT_EQ(a.status, ReadStatus::sample);
  ASSERT_EQ(b.status, ReadStatus::sample);
  EXPECT_GT(b.sample.t_ns, a.sample.t_ns);  // 2^63 - 1 ns later: saturated, not wrapped
  ReadResult c = src.next(std::chrono::seconds(1));  // a second pass would start past int64
  ASSERT_EQ(c.status, ReadStatus::error);
  EXPECT_NE(c.error.message.find("--loop: the log spans too long a time to repeat it"), std::string::npos) << c.error.message;
}

TEST(ExtremeNumbers, OutOfRangeIsNotReportedAsNotANumber) {
  test::TempDir d;
  test::write_file(d.path("n.csv"), kHeader + row("0", "1e308"));
  auto r = foveal_cli("log validate " + d.path("n.csv"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(":4: left_dir_x: '1e308' is out of range"), std::string::npos) << r.err;
  test::write_file(d.path("n.csv"), kHeader + row("0", "abc"));
  r = foveal_cli("log validate " + d.path("n.csv"));
  EXPECT_NE(r.err.find("'abc' is not a number"), std::string::npos) << r.err;
}

TEST(ExtremeNumbers, AHugePupilNormalKeepsItsDirection) {
  test::TempDir d;
  const std::string header =
      "gaze_timestamp,world_index,confidence,norm_pos_x,norm_pos_y,base_data,gaze_normal0_x,gaze_normal0_y,gaze_normal0_z\n";
  test::write_file(d.path("p.csv"), header + "1.0,1,0.9,0.5,0.5,x,1e30,1e30,1e30\n1.01,1,0.9,0.5,0.5,x,1e-30,0,-1e-30\n");
  auto r = foveal_cli("import --from pupil " + d.path("p.csv") + " --out " + d.path("o.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto samples = read_gaze_log(d.path("o.csv"));
  ASSERT_TRUE(samples) << samples.error().message;
  ASSERT_EQ(samples->size(), 2u);
  const EyeSample& e = (*samples)[0].eye(Eye::right);
  ASSERT_TRUE(e.has(kValidDirection));
  const float k = 1.0f / std::sqrt(3.0f);  // Pupil (x, y, z) -> foveal (x, -y, -z)
  EXPECT_NEAR(e.direction.x, k, 1e-6);
  EXPECT_NEAR(e.direction.y, -k, 1e-6);
  EXPECT_NEAR(e.direction.z, -k, 1e-6);
  const EyeSample& tiny = (*samples)[1].eye(Eye::right);
  ASSERT_TRUE(tiny.has(kValidDirection));
  EXPECT_NEAR(tiny.direction.x, std::sqrt(0.5f), 1e-6);
  EXPECT_NEAR(tiny.direction.z, std::sqrt(0.5f), 1e-6);
}

}  // namespace
}  // namespace foveal

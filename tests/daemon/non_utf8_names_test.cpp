// File names that are not UTF-8 (Linux names are bytes) in JSON output: every writer goes
// through json_text, which puts U+FFFD for such bytes instead of throwing (nlohmann's
// type_error 316 aborted foveald at shutdown, and `foveal log validate --json`).
// The names reach the programs through argv directly: no shell in between.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "test_support.hpp"

namespace foveal {
namespace {

constexpr int kGuardMs = 120'000;  // only a hang reaches it
const std::string kReplacement = "\xEF\xBF\xBD";  // U+FFFD in UTF-8

struct CliRun {
  int exit_code = -1;
  std::string out, err;
};

CliRun run(const test::TempDir& d, std::vector<std::string> argv, std::vector<std::string> env) {
  std::vector<char*> a, e;
  for (auto& s : argv) a.push_back(s.data());
  a.push_back(nullptr);
  for (auto& s : env) e.push_back(s.data());
  e.push_back(nullptr);
  const std::string out = d.path("stdout.txt"), err = d.path("stderr.txt");
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&fa, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  const int rc = ::posix_spawn(&pid, a[0], &fa, nullptr, a.data(), e.data());
  posix_spawn_file_actions_destroy(&fa);
  CliRun r;
  if (rc != 0) return r;
  r.exit_code = test::wait_for_exit(pid, kGuardMs);
  if (r.exit_code < 0) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
  }
  r.out = test::read_file(out);
  r.err = test::read_file(err);
  return r;
}

TEST(NonUtf8Names, LogValidateJsonReplacesTheBytesAndABadLogIsStillABadLog) {
  test::TempDir d;
  const std::string good = d.path("good_\xff.csv");
  std::filesystem::copy_file(test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv"), good);
  CliRun r = run(d, {test::bin("foveal"), "log", "validate", good, "--json"}, {"PATH=/usr/bin:/bin"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out, nullptr, false);
  ASSERT_FALSE(j.is_discarded()) << "not JSON: " << r.out;
  EXPECT_NE(r.out.find("good_" + kReplacement + ".csv"), std::string::npos) << r.out;

  const std::string bad = d.path("bad_\xff.csv");
  test::write_file(bad, "# foveal-gaze-log v2\nnot,a,log\n");
  r = run(d, {test::bin("foveal"), "log", "validate", bad, "--json"}, {"PATH=/usr/bin:/bin"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("bad_"), std::string::npos) << r.err;
}

TEST(NonUtf8Names, FovealdWritesItsSummaryIntoSuchAFolderAndRemovesItsBlock) {
  test::TempDir d;
  std::filesystem::create_directories(d.path("run"));
  std::filesystem::create_directories(d.path("config"));
  const std::string shm = "/foveal-test-utf8-" + std::to_string(::getpid());
  const std::string out = d.path("out_\xff");
  const CliRun r = run(d, {test::bin("foveald"), "--source", "synthetic", "--duration", "1", "--no-render", "-q", "--out", out},
                    {"XDG_RUNTIME_DIR=" + d.path("run"), "XDG_CONFIG_HOME=" + d.path("config"), "FOVEAL_SHM_NAME=" + shm,
                     "PATH=/usr/bin:/bin"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto summary = nlohmann::json::parse(test::read_file(out + "/summary.json"), nullptr, false);
  EXPECT_TRUE(summary.is_object()) << "no summary.json in " << out << "\n" << r.err;
  EXPECT_NE(test::read_file(out + "/summary.json").find(kReplacement), std::string::npos);
  std::error_code ec;
  EXPECT_FALSE(std::filesystem::exists("/dev/shm" + shm, ec)) << "foveald left its block /dev/shm" << shm;
  ::shm_unlink(shm.c_str());  // nothing left behind, whatever happened
}

}  // namespace
}  // namespace foveal

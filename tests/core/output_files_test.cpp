// What foveal writes over, and what it leaves behind (issue 15 items 1-3): only regular
// files are replaced, never an input; modes follow the umask or the old file; temporary
// files of killed writers do not pile up. docs/bad-input.md, "Files, sockets and shared memory".
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <thread>

#include "foveal/core/atomic_file.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

namespace fs = std::filesystem;

const std::string kVive = "data/gaze/vive_pro_eye/TESTNA01_2D_Fist3.csv";

std::vector<std::string> temporaries_of(const std::string& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(".tmp.") != std::string::npos) found.push_back(e.path().string());
  return found;
}

mode_t mode_of(const std::string& path) {
  struct stat st{};
  return ::lstat(path.c_str(), &st) == 0 ? st.st_mode : 0;
}

/// A character device like /dev/null, made in the test's directory (needs root).
bool make_null_device(const std::string& path) { return ::mknod(path.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0; }

TEST(OutputTargets, OnlyRegularFilesAreReplaced) {
  test::TempDir dir;
  ASSERT_EQ(::mkfifo(dir.path("fifo").c_str(), 0600), 0);
  ASSERT_EQ(::mkdir(dir.path("dir").c_str(), 0700), 0);
  const int sock = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strncpy(addr.sun_path, dir.path("sock").c_str(), sizeof addr.sun_path - 1);
  ASSERT_EQ(::bind(sock, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  test::write_file(dir.path("real"), "kept\n");
  ASSERT_EQ(::symlink(dir.path("real").c_str(), dir.path("link").c_str()), 0);
  std::vector<std::pair<std::string, std::string>> cases = {
      {"fifo", "is a FIFO"}, {"dir", "is a directory"}, {"sock", "is a socket"}, {"link", "is a symbolic link"}};
  if (make_null_device(dir.path("null"))) cases.push_back({"null", "is a character device"});
  for (const auto& [name, expected] : cases) {
    const std::string path = dir.path(name);
    const mode_t before = mode_of(path);
    auto f = AtomicFile::create(path);
    ASSERT_FALSE(f) << name;
    EXPECT_EQ(f.error().kind, ErrorKind::bad_input);
    EXPECT_NE(f.error().message.find(path + ": " + expected), std::string::npos) << f.error().message;
    EXPECT_EQ(mode_of(path), before) << name << " is left as it was";
  }
  ::close(sock);
  EXPECT_EQ(test::read_file(dir.path("real")), "kept\n");
  EXPECT_TRUE(temporaries_of(dir.path()).empty());
}

TEST(OutputTargets, ImportOntoACharacterDeviceExitsTwoAndLeavesIt) {
  test::TempDir dir;
  if (!make_null_device(dir.path("null"))) GTEST_SKIP() << "mknod needs root (CI runs as root)";
  auto r = test::run(test::bin("foveal") + " import --from sranipal " + test::source_path(kVive) + " --out " +
                     dir.path("null"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(dir.path("null") + ": is a character device"), std::string::npos) << r.err;
  EXPECT_TRUE(S_ISCHR(mode_of(dir.path("null"))));
  EXPECT_TRUE(temporaries_of(dir.path()).empty());
}

TEST(OutputTargets, ReplayTraceOntoAFifoExitsTwoWithoutBlocking) {
  test::TempDir dir;
  ASSERT_EQ(::mkfifo(dir.path("fifo").c_str(), 0600), 0);
  auto r = test::run("timeout 20 " + test::bin("foveal") + " replay " + test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv") +
                     " --trace " + dir.path("fifo"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(dir.path("fifo") + ": is a FIFO"), std::string::npos) << r.err;
  EXPECT_TRUE(S_ISFIFO(mode_of(dir.path("fifo"))));
}

TEST(OutputTargets, TheOutputMayNotBeTheInput) {
  test::TempDir dir;
  const std::string in = dir.path("in.csv"), linked = dir.path("hardlink.csv");
  fs::copy_file(test::source_path(kVive), in);
  ASSERT_EQ(::link(in.c_str(), linked.c_str()), 0);
  const std::string original = test::read_file(in);
  for (const std::string& out : {in, linked, dir.path("./in.csv")}) {
    auto r = test::run(test::bin("foveal") + " import --from sranipal " + in + " --out " + out);
    EXPECT_EQ(r.exit_code, 2) << out << ": " << r.err;
    EXPECT_NE(r.err.find(out + ": is the input " + in), std::string::npos) << r.err;
  }
  EXPECT_EQ(test::read_file(in), original);
  // replay --trace onto its log, and onto its --config
  const std::string log = dir.path("log.csv");
  ASSERT_EQ(test::run(test::bin("foveal") + " import --from sranipal " + in + " --out " + log).exit_code, 0);
  const std::string log_bytes = test::read_file(log);
  auto r = test::run(test::bin("foveal") + " replay " + log + " --trace " + log);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(log + ": is the input " + log), std::string::npos) << r.err;
  EXPECT_EQ(test::read_file(log), log_bytes);
  test::write_file(dir.path("filter.json"), "{}\n");
  r = test::run(test::bin("foveal") + " replay " + log + " --config " + dir.path("filter.json") + " --trace " +
                dir.path("filter.json"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(test::read_file(dir.path("filter.json")), "{}\n");
}

TEST(OutputTargets, ProfileExportOntoTheStoredProfileExitsTwo) {
  test::TempDir dir;
  const std::string env = "XDG_CONFIG_HOME=" + dir.path() + " " + test::bin("foveal") + " profile ";
  ASSERT_EQ(test::run(env + "create alice").exit_code, 0);
  const std::string stored = dir.path("foveal/profiles/alice.json");
  const std::string before = test::read_file(stored);
  auto r = test::run(env + "export alice " + stored);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(stored + ": is the input"), std::string::npos) << r.err;
  EXPECT_EQ(test::read_file(stored), before);
}

class UmaskScope {
 public:
  explicit UmaskScope(mode_t m) : old_(::umask(m)) {}
  ~UmaskScope() { ::umask(old_); }

 private:
  mode_t old_;
};

TEST(OutputModes, NewFilesFollowTheUmaskAndExistingFilesKeepTheirMode) {
  test::TempDir dir;
  {
    UmaskScope u(077);
    ASSERT_TRUE(write_file_atomically(dir.path("private"), "x"));
  }
  EXPECT_EQ(mode_of(dir.path("private")) & 07777, 0600u);
  {
    UmaskScope u(022);
    ASSERT_TRUE(write_file_atomically(dir.path("public"), "x"));
    EXPECT_EQ(mode_of(dir.path("public")) & 07777, 0644u);
    // An existing file keeps its bits, narrower or wider than the umask's.
    for (mode_t m : {0600, 0640, 0664, 0400}) {
      const std::string p = dir.path("kept" + std::to_string(m));
      test::write_file(p, "old");
      ASSERT_EQ(::chmod(p.c_str(), m), 0);
      ASSERT_TRUE(write_file_atomically(p, "new"));
      EXPECT_EQ(mode_of(p) & 07777, m) << std::oct << m;
      EXPECT_EQ(test::read_file(p), "new");
    }
  }
  UmaskScope u(027);  // through the CLI: a gaze log
  auto r = test::run(test::bin("foveal") + " import --from sranipal " + test::source_path(kVive) + " --out " +
                     dir.path("log.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(mode_of(dir.path("log.csv")) & 07777, 0640u);
}

/// A temporary file as a killed writer leaves it: `age_s` seconds old, nobody's lock.
void plant_temporary(const std::string& path, int age_s) {
  test::write_file(path, "partial");
  const timespec t[2] = {{::time(nullptr) - age_s, 0}, {::time(nullptr) - age_s, 0}};
  ASSERT_EQ(::utimensat(AT_FDCWD, path.c_str(), t, 0), 0);
}

TEST(OutputTemporaries, StaleOnesOfTheSameTargetAreRemovedOnTheNextWrite) {
  test::TempDir dir;
  const std::string out = dir.path("out.csv");
  plant_temporary(out + ".tmp.Ab3dE9", 60);    // stale: removed
  plant_temporary(out + ".tmp.Zz0000", 3600);  // stale: removed
  plant_temporary(out + ".tmp.fresh1", 0);     // may be a writer between create and lock: kept
  plant_temporary(out + ".tmp.toolong1", 60);  // not our naming: kept
  plant_temporary(dir.path("other.csv.tmp.Ab3dE9"), 60);  // another target's: kept
  plant_temporary(out + ".tmp.locked", 60);    // a live writer holds it: kept
  const int held = ::open((out + ".tmp.locked").c_str(), O_RDONLY);
  ASSERT_EQ(::flock(held, LOCK_EX), 0);
  ASSERT_TRUE(write_file_atomically(out, "complete"));
  ::close(held);
  EXPECT_FALSE(fs::exists(out + ".tmp.Ab3dE9"));
  EXPECT_FALSE(fs::exists(out + ".tmp.Zz0000"));
  EXPECT_TRUE(fs::exists(out + ".tmp.fresh1"));
  EXPECT_TRUE(fs::exists(out + ".tmp.toolong1"));
  EXPECT_TRUE(fs::exists(dir.path("other.csv.tmp.Ab3dE9")));
  EXPECT_TRUE(fs::exists(out + ".tmp.locked"));
  EXPECT_EQ(test::read_file(out), "complete");
}

TEST(OutputTemporaries, AnotherUsersAreNeverRemoved) {
  if (::geteuid() != 0) GTEST_SKIP() << "chown to another uid needs root (CI runs as root)";
  test::TempDir dir;
  const std::string out = dir.path("out.csv");
  plant_temporary(out + ".tmp.Ab3dE9", 60);
  ASSERT_EQ(::chown((out + ".tmp.Ab3dE9").c_str(), 4242, 4242), 0);
  ASSERT_TRUE(write_file_atomically(out, "complete"));
  EXPECT_TRUE(fs::exists(out + ".tmp.Ab3dE9"));
}

/// Starts a long `foveal synth` and returns its pid once its temporary file exists.
pid_t start_long_write(const std::string& out, std::string& tmp) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execl(test::bin("foveal").c_str(), "foveal", "synth", "--duration", "36000", "--out", out.c_str(), nullptr);
    ::_exit(127);
  }
  const std::string dir = fs::path(out).parent_path().string();
  test::eventually([&] {
    const auto t = temporaries_of(dir);
    if (!t.empty()) tmp = t.front();
    return !t.empty();
  });
  return pid;
}

TEST(OutputTemporaries, SigtermAndSigintMidWriteLeaveNoTemporaryFile) {
  for (int sig : {SIGTERM, SIGINT}) {
    test::TempDir dir;
    std::string tmp;
    const pid_t pid = start_long_write(dir.path("log.csv"), tmp);
    ASSERT_FALSE(tmp.empty()) << "no temporary file appeared";
    ASSERT_EQ(::kill(pid, sig), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "dies of the signal, as before";
    EXPECT_TRUE(temporaries_of(dir.path()).empty()) << strsignal(sig);
    EXPECT_FALSE(fs::exists(dir.path("log.csv")));
  }
}

TEST(OutputTemporaries, ASigkilledWritersTemporaryGoesWithTheNextWrite) {
  test::TempDir dir;
  std::string tmp;
  const pid_t pid = start_long_write(dir.path("log.csv"), tmp);
  ASSERT_FALSE(tmp.empty()) << "no temporary file appeared";
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  ::waitpid(pid, nullptr, 0);
  ASSERT_TRUE(fs::exists(tmp)) << "SIGKILL cannot be caught: the file stays until the next write";
  const timespec t[2] = {{::time(nullptr) - 10, 0}, {::time(nullptr) - 10, 0}};  // as if written a while ago
  ASSERT_EQ(::utimensat(AT_FDCWD, tmp.c_str(), t, 0), 0);
  auto r = test::run(test::bin("foveal") + " synth --duration 1 --out " + dir.path("log.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(tmp));
  EXPECT_TRUE(temporaries_of(dir.path()).empty());
}

}  // namespace
}  // namespace foveal

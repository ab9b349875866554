// Where the control socket may live: a private directory of this user, and nothing but
// a stale socket is ever replaced (docs/daemon.md). The attacks of issue 15 items 5
// and 6, replayed, the second one by another user in a private /tmp.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "foveal/runtime/control_server.hpp"
#include "other_user.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

mode_t mode_of(const std::string& path) {
  struct stat st{};
  return ::lstat(path.c_str(), &st) == 0 ? st.st_mode & 07777 : 0;
}

TEST(ControlSocketPlace, ARegularFileAtThePathIsRefusedAndKept) {
  test::TempDir dir;
  const std::string path = dir.path("control.sock");
  test::write_file(path, "precious\n");
  auto s = ControlServer::listen(path);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find(path + ": exists and is not a socket"), std::string::npos) << s.error().message;
  EXPECT_EQ(test::read_file(path), "precious\n");
}

TEST(ControlSocketPlace, AnExistingDirectoryOpenToOthersIsRefusedNotChmodded) {
  test::TempDir dir;
  for (mode_t mode : {01777, 0750, 0701}) {
    const std::string sub = dir.path("d" + std::to_string(mode));
    ASSERT_EQ(::mkdir(sub.c_str(), 0700), 0);
    ASSERT_EQ(::chmod(sub.c_str(), mode), 0);
    auto s = ControlServer::listen(sub + "/control.sock");
    ASSERT_FALSE(s) << std::oct << mode;
    EXPECT_NE(s.error().message.find(sub + ": has mode"), std::string::npos) << s.error().message;
    EXPECT_EQ(mode_of(sub), mode) << "the directory is left as it was";
    EXPECT_FALSE(std::filesystem::exists(sub + "/control.sock"));
  }
}

TEST(ControlSocketPlace, ASymlinkedDirectoryIsRefused) {
  test::TempDir dir;
  ASSERT_EQ(::mkdir(dir.path("real").c_str(), 0700), 0);
  ASSERT_EQ(::symlink(dir.path("real").c_str(), dir.path("link").c_str()), 0);
  auto s = ControlServer::listen(dir.path("link/control.sock"));
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("symbolic link"), std::string::npos) << s.error().message;
}

TEST(ControlSocketPlace, MissingDirectoriesAreCreatedPrivate) {
  test::TempDir dir;
  auto s = ControlServer::listen(dir.path("a/b/control.sock"));
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(mode_of(dir.path("a")), 0700u);
  EXPECT_EQ(mode_of(dir.path("a/b")), 0700u);
  EXPECT_EQ(mode_of(dir.path("a/b/control.sock")), 0600u);
}

/// Binds a socket at `path` and closes it: what a crashed daemon leaves.
void leave_stale_socket(const std::string& path) {
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strncpy(addr.sun_path, path.c_str(), sizeof addr.sun_path - 1);
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  ::close(fd);
}

TEST(ControlSocketPlace, OnlyAStaleSocketIsReplaced) {
  test::TempDir dir;
  const std::string path = dir.path("control.sock");
  leave_stale_socket(path);
  const mode_t stale_mode = mode_of(path);
  ASSERT_EQ(::chmod(path.c_str(), 0644), 0);  // tell the old socket from the new one
  auto s = ControlServer::listen(path);
  ASSERT_TRUE(s) << s.error().message;
  struct stat st{};
  ASSERT_EQ(::lstat(path.c_str(), &st), 0);
  EXPECT_TRUE(S_ISSOCK(st.st_mode));
  EXPECT_EQ(st.st_mode & 0777, 0600u) << "a new socket (the stale one was " << std::oct << stale_mode << ")";
}

// Issue 15 item 6: without XDG_RUNTIME_DIR the socket goes to /tmp/foveal-<uid>. Another
// user makes that directory first, mode 0777, and listens there with a spoofing server.
// The victim's foveald must refuse the directory and the victim's `foveal ctl` must not
// believe a server of another user.
TEST(ControlSocketPlace, AnotherUsersFallbackDirectoryIsRefused) {
  FOVEAL_REQUIRE_ROOT();
  test::TempUser attacker, victim;
  ASSERT_TRUE(attacker.ok() && victim.ok()) << "useradd failed";
  const int rc = test::in_child([&] {
    if (!test::private_tmpfs("/tmp")) return 10;
    const std::string dir = "/tmp/foveal-" + std::to_string(victim.uid());
    int ready[2];
    if (::pipe(ready) != 0) return 11;
    const pid_t spoofer = ::fork();
    if (spoofer == 0) {  // the attacker: the victim's directory, 0777, and a fake daemon in it
      if (!test::become(attacker) || ::mkdir(dir.c_str(), 0777) != 0 || ::chmod(dir.c_str(), 0777) != 0) ::_exit(12);
      const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
      sockaddr_un addr{};
      addr.sun_family = AF_UNIX;
      std::snprintf(addr.sun_path, sizeof addr.sun_path, "%s/control.sock", dir.c_str());
      ::umask(0);
      if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 || ::listen(fd, 4) != 0) ::_exit(13);
      (void)!::write(ready[1], "r", 1);
      for (;;) {
        const int c = ::accept(fd, nullptr, nullptr);
        if (c < 0) ::_exit(0);
        const char spoof[] = "{\"ok\":true,\"state\":\"running\",\"spoofed\":true}\n";
        (void)!::write(c, spoof, sizeof spoof - 1);
        ::close(c);
      }
    }
    char b;
    if (::read(ready[0], &b, 1) != 1) return 14;
    const int victim_rc = test::in_child([&] {
      if (!test::become(victim)) return 20;
      ::unsetenv("XDG_RUNTIME_DIR");
      const std::string path = default_control_socket_path();
      if (path != dir + "/control.sock") return 21;
      auto s = ControlServer::listen(path);
      if (s) return 22;
      std::fprintf(stderr, "foveald as the victim: %s\n", s.error().message.c_str());
      if (s.error().message.find(dir + ": belongs to uid " + std::to_string(attacker.uid())) == std::string::npos)
        return 23;
      auto r = control_request(path, {{"cmd", "status"}}, 1000);
      if (r) {
        std::fprintf(stderr, "the victim's client believed: %s\n", r->dump().c_str());
        return 24;
      }
      std::fprintf(stderr, "foveal ctl as the victim: %s\n", r.error().message.c_str());
      if (r.error().message.find("uid " + std::to_string(attacker.uid())) == std::string::npos) return 25;
      return 0;
    });
    ::kill(spoofer, SIGKILL);
    ::waitpid(spoofer, nullptr, 0);
    return victim_rc;
  });
  EXPECT_EQ(rc, 0) << "see the child's stderr: 1x set-up, 22 listen accepted the directory, 23 wrong message, "
                      "24 the client took the spoofed reply, 25 its message does not name the other uid";
}

}  // namespace
}  // namespace foveal

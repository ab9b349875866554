#pragma once
// A second user for tests of what one user can do to another's files, sockets and
// shared memory. Needs root (the CI machine runs the tests as root): a uniquely named
// system user is created with useradd and removed at scope exit, also when the test
// fails. Work as that user, or in a private /tmp or /dev/shm, runs in child processes.
#include <grp.h>
#include <pwd.h>
#include <sched.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <thread>

namespace foveal::test {

inline bool is_root() { return ::geteuid() == 0; }

/// Say so, never pass silently: a test that needs a second user is skipped, with this
/// reason, only when it does not run as root.
#define FOVEAL_REQUIRE_ROOT()                                                                         \
  do {                                                                                                \
    if (!::foveal::test::is_root())                                                                   \
      GTEST_SKIP() << "needs root to create a second user (useradd); CI runs the tests as root";     \
  } while (0)

class TempUser {
 public:
  TempUser() {
    static std::atomic<int> counter{0};
    name_ = "fovtest" + std::to_string(::getpid()) + "x" + std::to_string(counter++);
    const std::string add =
        "useradd --system --no-create-home --user-group --shell /usr/sbin/nologin " + name_ + " >/dev/null 2>&1";
    // Parallel tests contend for /etc/passwd's lock: retried until it is free (the
    // deadline only a hang guard, as a loaded machine holds the lock longer).
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!ok_ && std::chrono::steady_clock::now() < until) {
      if (std::system(add.c_str()) == 0) ok_ = true;
      else std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    if (!ok_) return;
    const passwd* pw = ::getpwnam(name_.c_str());
    if (!pw) return;
    uid_ = pw->pw_uid;
    gid_ = pw->pw_gid;
  }
  ~TempUser() {
    if (!ok_) return;
    const std::string del = "userdel " + name_ + " >/dev/null 2>&1";
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::system(del.c_str()) != 0 && std::chrono::steady_clock::now() < until)
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    (void)std::system(("groupdel " + name_ + " >/dev/null 2>&1").c_str());  // where userdel left the group
  }
  TempUser(const TempUser&) = delete;
  TempUser& operator=(const TempUser&) = delete;

  bool ok() const { return ok_ && uid_ != 0; }
  const std::string& name() const { return name_; }
  uid_t uid() const { return uid_; }
  gid_t gid() const { return gid_; }

 private:
  std::string name_;
  bool ok_ = false;
  uid_t uid_ = 0;
  gid_t gid_ = 0;
};

/// Runs `body` in a forked child and returns its exit code (128 + signal if it died).
/// The child reports through its exit code and stderr; gtest assertions stay in the parent.
inline int in_child(const std::function<int()>& body) {
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    int rc = 99;
    try {
      rc = body();
    } catch (...) {
    }
    std::fflush(nullptr);
    ::_exit(rc);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/// In a child: drops root for `user` (no supplementary groups), as setpriv
/// --reuid/--regid --clear-groups would.
inline bool become(const TempUser& user) {
  return ::setgroups(0, nullptr) == 0 && ::setgid(user.gid()) == 0 && ::setuid(user.uid()) == 0;
}

/// In a child: a private mount namespace with an empty tmpfs over `dir` (/tmp, /dev/shm),
/// so that what the test plants there cannot meet anything real.
inline bool private_tmpfs(const char* dir) {
  return ::unshare(CLONE_NEWNS) == 0 && ::mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) == 0 &&
         ::mount("tmpfs", dir, "tmpfs", MS_NOSUID | MS_NODEV, "mode=1777") == 0;
}

}  // namespace foveal::test

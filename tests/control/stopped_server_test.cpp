// A stopped server (foveald under SIGSTOP, or never polling) whose listen backlog is
// full: a blocking connect() to it waits until killed. Every client call and the
// already-running probe of listen() give up in time instead.
#include <gtest/gtest.h>

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include "foveal/core/clock.hpp"
#include "foveal/runtime/control_server.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

/// Connections queued on `path` without being accepted, until one more would block.
struct FilledBacklog {
  explicit FilledBacklog(const std::string& path) {
    sockaddr_un a{};
    a.sun_family = AF_UNIX;
    std::strncpy(a.sun_path, path.c_str(), sizeof a.sun_path - 1);
    for (int i = 0; i < 10000; ++i) {
      const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
      if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
        EXPECT_EQ(errno, EAGAIN) << std::strerror(errno);
        ::close(fd);
        full = true;
        return;
      }
      fds.push_back(fd);
    }
  }
  ~FilledBacklog() {
    for (int fd : fds) ::close(fd);
  }
  std::vector<int> fds;
  bool full = false;
};

TEST(StoppedControlServer, RequestsTimeOutInsteadOfBlockingInConnect) {
  test::TempDir dir;
  auto server = ControlServer::listen(dir.path("run/control.sock"));  // never polled: stopped
  ASSERT_TRUE(server) << server.error().message;
  FilledBacklog backlog(server->path());
  ASSERT_TRUE(backlog.full);
  for (int i = 0; i < 20; ++i) {
    const TimeNs t0 = monotonic_now_ns();
    auto r = control_request(server->path(), {{"cmd", "status"}}, 100);
    const TimeNs took = monotonic_now_ns() - t0;
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("not accepting connections within 100 ms"), std::string::npos) << r.error().message;
    ASSERT_LT(took, test::kReturnsWithinNs) << "request " << i + 1 << " took " << took / kNsPerMs << " ms";
  }
}

TEST(StoppedControlServer, ASecondServerSeesItAliveAtOnce) {
  // The already-running probe: a full backlog is a live server, not a stale socket, and
  // finding that out must not wait for it.
  test::TempDir dir;
  auto first = ControlServer::listen(dir.path("run/control.sock"));
  ASSERT_TRUE(first) << first.error().message;
  FilledBacklog backlog(first->path());
  ASSERT_TRUE(backlog.full);
  const TimeNs t0 = monotonic_now_ns();
  auto second = ControlServer::listen(first->path());
  EXPECT_LT(monotonic_now_ns() - t0, test::kReturnsWithinNs);
  ASSERT_FALSE(second);
  EXPECT_NE(second.error().message.find("already listening"), std::string::npos) << second.error().message;
}

}  // namespace
}  // namespace foveal

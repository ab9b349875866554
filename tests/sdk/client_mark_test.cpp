// foveal_client_mark against the runtime's real ControlServer on a real Unix socket: the
// request foveald's handler sees, its reply's time, a refusal's reason, a server that
// never answers, one whose backlog is full, nobody listening, and text the runtime would
// refuse. (A real foveald takes the marker into its trace in tests/sdk/install_test.sh;
// a stopped one with a full backlog is in tests/daemon/foveald_integration_test.cpp.)
#include <gtest/gtest.h>

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "foveal/client.h"
#include "foveal/core/clock.hpp"
#include "foveal/runtime/control_server.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

/// A ControlServer polled on its own thread with the test's handler.
struct Server {
  Server(const std::string& path, ControlServer::Handler h) : handler(std::move(h)) {
    auto s = ControlServer::listen(path);
    if (!s) {
      ADD_FAILURE() << s.error().message;
      return;
    }
    server.emplace(std::move(*s));
    thread = std::thread([this] {
      while (!stop) server->poll(20, handler);
    });
  }
  ~Server() {
    stop = true;
    if (thread.joinable()) thread.join();
  }
  ControlServer::Handler handler;
  std::optional<ControlServer> server;
  std::atomic<bool> stop{false};
  std::thread thread;
};

TEST(FovealClientMark, SendsTheTextAndReturnsTheStamp) {
  test::TempDir d;
  const std::string path = d.path("run/control.sock");
  std::mutex m;  // the server's thread writes, this one reads (the socket is no fence TSan sees)
  std::string seen;
  Server s(path, [&](const nlohmann::json& req) -> nlohmann::json {
    if (req.value("cmd", "") != "mark") return {{"ok", false}, {"error", "not a mark"}};
    std::lock_guard lock(m);
    seen = req.value("text", "");
    return {{"ok", true}, {"t_ns", 1234567890123}, {"markers", 1}};
  });
  foveal_error err{};
  std::int64_t t = 0;
  const char* text = "trial 3 \"start\", back\\slash";
  ASSERT_EQ(foveal_client_mark(path.c_str(), text, 2000, &t, &err), FOVEAL_OK) << err.message;
  EXPECT_EQ(t, 1234567890123);
  std::lock_guard lock(m);
  EXPECT_EQ(seen, text);  // quotes and backslashes survive the request's escaping
}

TEST(FovealClientMark, ARefusalCarriesFovealdsReason) {
  test::TempDir d;
  const std::string path = d.path("run/control.sock");
  Server s(path, [](const nlohmann::json&) -> nlohmann::json {
    return {{"ok", false}, {"error", "mark: 64 markers wait for the next sample already; refused"}};
  });
  foveal_error err{};
  EXPECT_EQ(foveal_client_mark(path.c_str(), "x", 2000, nullptr, &err), FOVEAL_ERR_REFUSED);
  EXPECT_EQ(err.code, FOVEAL_ERR_REFUSED);
  EXPECT_NE(std::string(err.message).find("64 markers wait"), std::string::npos) << err.message;
  EXPECT_NE(std::string(err.message).find(path), std::string::npos) << err.message;
}

TEST(FovealClientMark, ASilentServerTimesOut) {
  test::TempDir d;
  const std::string path = d.path("silent.sock");
  // Listening, never accepting: connect() succeeds through the backlog, no reply comes.
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un a{};
  a.sun_family = AF_UNIX;
  std::strncpy(a.sun_path, path.c_str(), sizeof a.sun_path - 1);
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  ASSERT_EQ(::listen(fd, 4), 0);
  foveal_error err{};
  EXPECT_EQ(foveal_client_mark(path.c_str(), "x", 200, nullptr, &err), FOVEAL_ERR_TIMEOUT);
  EXPECT_NE(std::string(err.message).find("200 ms"), std::string::npos) << err.message;
  ::close(fd);
}

/// A listening socket that never accepts, its backlog filled as a stopped foveald's is:
/// connections queued until one more would block.
struct FullBacklog {
  explicit FullBacklog(const std::string& path) {
    listen_fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_un a{};
    a.sun_family = AF_UNIX;
    std::strncpy(a.sun_path, path.c_str(), sizeof a.sun_path - 1);
    EXPECT_EQ(::bind(listen_fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
    EXPECT_EQ(::listen(listen_fd, 4), 0);
    for (int i = 0; i < 1000; ++i) {
      const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
      if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
        EXPECT_EQ(errno, EAGAIN) << std::strerror(errno);
        ::close(fd);
        full = true;
        break;
      }
      queued.push_back(fd);
    }
  }
  ~FullBacklog() {
    for (int fd : queued) ::close(fd);
    ::close(listen_fd);
  }
  int listen_fd = -1;
  std::vector<int> queued;
  bool full = false;
};

TEST(FovealClientMark, AFullBacklogTimesOutInsteadOfBlocking) {
  // A blocking connect waited here until killed: the timeout now covers connecting too.
  test::TempDir d;
  const std::string path = d.path("stopped.sock");
  FullBacklog backlog(path);
  ASSERT_TRUE(backlog.full);
  for (int i = 0; i < 100; ++i) {
    foveal_error err{};
    const TimeNs t0 = monotonic_now_ns();
    ASSERT_EQ(foveal_client_mark(path.c_str(), "x", 100, nullptr, &err), FOVEAL_ERR_TIMEOUT) << err.message;
    const TimeNs took = monotonic_now_ns() - t0;
    ASSERT_LT(took, test::kReturnsWithinNs) << "call " << i + 1 << " took " << took / kNsPerMs << " ms";
    EXPECT_NE(std::string(err.message).find("within 100 ms"), std::string::npos) << err.message;
  }
}

TEST(FovealClientMark, NobodyListeningIsNoWriter) {
  test::TempDir d;
  foveal_error err{};
  EXPECT_EQ(foveal_client_mark(d.path("none.sock").c_str(), "x", 200, nullptr, &err), FOVEAL_ERR_NO_WRITER);
  EXPECT_NE(std::string(err.message).find("is foveald running?"), std::string::npos) << err.message;
  // The defaults: nobody at $XDG_RUNTIME_DIR/foveal/control.sock either.
  ::setenv("XDG_RUNTIME_DIR", d.path().c_str(), 1);
  EXPECT_EQ(foveal_client_mark(nullptr, "x", 200, nullptr, &err), FOVEAL_ERR_NO_WRITER);
  EXPECT_NE(std::string(err.message).find(d.path("foveal/control.sock")), std::string::npos) << err.message;
}

TEST(FovealClientMark, TextTheRuntimeWouldRefuseIsAnInvalidArgument) {
  test::TempDir d;
  const std::string path = d.path("run/control.sock");
  std::atomic<int> requests{0};
  Server s(path, [&](const nlohmann::json&) -> nlohmann::json {
    ++requests;
    return {{"ok", true}, {"t_ns", 1}};
  });
  foveal_error err{};
  EXPECT_EQ(foveal_client_mark(path.c_str(), nullptr, 200, nullptr, &err), FOVEAL_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(foveal_client_mark(path.c_str(), "", 200, nullptr, &err), FOVEAL_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(foveal_client_mark(path.c_str(), "two\nlines", 200, nullptr, &err), FOVEAL_ERR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(err.message).find("byte 4"), std::string::npos) << err.message;
  EXPECT_EQ(foveal_client_mark(path.c_str(), std::string(257, 'x').c_str(), 200, nullptr, &err), FOVEAL_ERR_INVALID_ARGUMENT);
  // Not UTF-8 (foveald's JSON parser refused these as a malformed request, REFUSED): a
  // stray continuation byte, a cut sequence, an overlong '/', a surrogate, above U+10FFFF.
  for (const char* bad : {"a\x80" "b", "trial \xc3", "\xc0\xaf", "\xed\xa0\x80", "\xf4\x90\x80\x80", "\xff"}) {
    EXPECT_EQ(foveal_client_mark(path.c_str(), bad, 200, nullptr, &err), FOVEAL_ERR_INVALID_ARGUMENT) << err.message;
    EXPECT_NE(std::string(err.message).find("not valid UTF-8"), std::string::npos) << err.message;
  }
  EXPECT_NE(std::string(err.message).find("byte 1"), std::string::npos) << err.message;
  EXPECT_EQ(foveal_client_mark(path.c_str(), "\xc3\xa9t\xc3\xa9 \xe2\x82\xac \xf0\x9f\x91\x81", 2000, nullptr, &err), FOVEAL_OK)
      << err.message;  // é, €, an eye: fine
  EXPECT_EQ(foveal_client_mark(path.c_str(), std::string(256, 'x').c_str(), 2000, nullptr, &err), FOVEAL_OK) << err.message;
  EXPECT_EQ(requests.load(), 2);
}

}  // namespace
}  // namespace foveal

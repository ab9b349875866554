// foveal_client_mark against the runtime's real ControlServer on a real Unix socket: the
// request foveald's handler sees, its reply's time, a refusal's reason, a server that
// never answers, nobody listening, and text the runtime would refuse. (A real foveald
// takes the marker into its trace in tests/sdk/install_test.sh.)
#include <gtest/gtest.h>

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "foveal/client.h"
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
  EXPECT_EQ(foveal_client_mark(path.c_str(), std::string(256, 'x').c_str(), 2000, nullptr, &err), FOVEAL_OK) << err.message;
  EXPECT_EQ(requests.load(), 1);
}

}  // namespace
}  // namespace foveal

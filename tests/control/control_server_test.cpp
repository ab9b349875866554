// The control socket over a real Unix socket: a server thread polls, clients talk.
#include <gtest/gtest.h>

#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <thread>

#include "control_fixture.hpp"

namespace foveal {
namespace {

using control_test::ControlSocket;

TEST_F(ControlSocket, AnswersRequestsAndIsPrivate) {
  auto r = control_request(path_, {{"cmd", "status"}});
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ((*r)["ok"], true);
  EXPECT_EQ((*r)["echo"]["cmd"], "status");
  struct stat st{};
  ASSERT_EQ(::stat(path_.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  ASSERT_EQ(::stat(dir_.path("run/foveal").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0700u);
}

TEST_F(ControlSocket, MalformedRequestsGetAnErrorAndTheServerGoesOn) {
  const int fd = connect_raw();
  for (const char* bad : {"not json\n", "[1,2,3]\n", "{\"cmd\": \n", "\"just a string\"\n"}) {
    ASSERT_GT(::send(fd, bad, std::strlen(bad), 0), 0);
    const auto reply = nlohmann::json::parse(read_line(fd));
    EXPECT_EQ(reply["ok"], false) << bad;
    EXPECT_NE(reply["error"].get<std::string>().find("malformed"), std::string::npos);
  }
  // Same connection still works.
  const char* good = "{\"cmd\":\"status\"}\n";
  ASSERT_GT(::send(fd, good, std::strlen(good), 0), 0);
  EXPECT_EQ(nlohmann::json::parse(read_line(fd))["ok"], true);
  ::close(fd);
  EXPECT_EQ(handled_.load(), 1);
}

TEST_F(ControlSocket, PartialMessagesAreJoined) {
  const int fd = connect_raw();
  ASSERT_GT(::send(fd, "{\"cmd\":", 7, 0), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // let the server see half a line
  ASSERT_GT(::send(fd, "\"fovea\"}\n{\"cmd\":\"status\"}\n", 26, 0), 0);
  EXPECT_EQ(nlohmann::json::parse(read_line(fd))["echo"]["cmd"], "fovea");
  EXPECT_EQ(nlohmann::json::parse(read_line(fd))["echo"]["cmd"], "status");
  ::close(fd);
}

TEST_F(ControlSocket, OversizedRequestIsRefusedAndOthersAreServed) {
  const int fd = connect_raw();
  const std::string huge(ControlServer::kMaxMessageBytes + 4096, 'x');
  std::size_t off = 0;
  while (off < huge.size()) {
    const ssize_t n = ::send(fd, huge.data() + off, huge.size() - off, MSG_NOSIGNAL);
    if (n <= 0) break;
    off += static_cast<std::size_t>(n);
  }
  const auto reply = nlohmann::json::parse(read_line(fd));
  EXPECT_EQ(reply["ok"], false);
  EXPECT_NE(reply["error"].get<std::string>().find("longer than"), std::string::npos);
  ::close(fd);
  auto r = control_request(path_, {{"cmd", "status"}});
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ((*r)["ok"], true);
}

TEST_F(ControlSocket, ASecondServerOnTheSamePathIsRefused) {
  auto second = ControlServer::listen(path_);
  ASSERT_FALSE(second);
  EXPECT_NE(second.error().message.find("already listening"), std::string::npos);
}

TEST(ControlSocketStale, AStaleSocketFileIsReplaced) {
  test::TempDir dir;
  const std::string path = dir.path("c.sock");
  { auto first = ControlServer::listen(path); ASSERT_TRUE(first); }
  // Leave a socket file behind as a crashed daemon would.
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strncpy(addr.sun_path, path.c_str(), sizeof addr.sun_path - 1);
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  ::close(fd);
  auto again = ControlServer::listen(path);
  EXPECT_TRUE(again) << again.error().message;
}

TEST(ControlClient, NoDaemonIsAClearError) {
  test::TempDir dir;
  auto r = control_request(dir.path("none.sock"), {{"cmd", "status"}});
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("is foveald running"), std::string::npos);
}

}  // namespace
}  // namespace foveal

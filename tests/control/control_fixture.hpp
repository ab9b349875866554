#pragma once
// A control server on a real Unix socket, polled by its own thread as foveald polls it,
// and raw clients for messages the well-behaved control_request() never sends.
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
#include <vector>

#include "foveal/runtime/control_server.hpp"
#include "test_support.hpp"

namespace foveal::control_test {

class ControlSocket : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = dir_.path("run/foveal/control.sock");
    auto s = ControlServer::listen(path_);
    ASSERT_TRUE(s) << s.error().message;
    server_.emplace(std::move(s.value()));
    server_->set_logger([this](const std::string& m) {
      std::lock_guard<std::mutex> lock(log_mutex_);
      log_.push_back(m);
    });
    thread_ = std::thread([this] {
      while (!stop_) server_->poll(20, [this](const nlohmann::json& req) { return handle(req); });
    });
  }
  void TearDown() override { stop_server(); }
  /// After this the test may look at the server directly.
  void stop_server() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }

  nlohmann::json handle(const nlohmann::json& req) {
    ++handled_;
    // A handler that trusts a field's type, as a real one may.
    if (req["cmd"] == "typed") return {{"ok", true}, {"value", req.at("value").get<int>()}};
    if (req["cmd"] == "big") return {{"ok", true}, {"padding", std::string(2000, 'p')}};  // about a status reply
    return {{"ok", true}, {"echo", req}};
  }

  int connect_raw() {
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::strncpy(addr.sun_path, path_.c_str(), sizeof addr.sun_path - 1);
    EXPECT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0) << std::strerror(errno);
    return fd;
  }
  static std::string read_line(int fd) {
    std::string s;
    char c;
    while (::recv(fd, &c, 1, 0) == 1 && c != '\n') s += c;
    return s;
  }
  static void send_text(int fd, const std::string& text) {
    ASSERT_EQ(::send(fd, text.data(), text.size(), MSG_NOSIGNAL), static_cast<ssize_t>(text.size()));
  }
  std::vector<std::string> log_lines() {
    std::lock_guard<std::mutex> lock(log_mutex_);
    return log_;
  }

  test::TempDir dir_;
  std::string path_;
  std::optional<ControlServer> server_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<int> handled_{0};
  std::mutex log_mutex_;
  std::vector<std::string> log_;
};

}  // namespace foveal::control_test

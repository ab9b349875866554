#include "foveal/runtime/control_server.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <utility>

#include "foveal/core/clock.hpp"
#include "foveal/core/json_file.hpp"

namespace foveal {

namespace {

Result<sockaddr_un> address(const std::string& path) {
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  if (path.size() >= sizeof addr.sun_path) return bad_input(path + ": socket path too long");
  std::memcpy(addr.sun_path, path.c_str(), path.size() + 1);
  return addr;
}

nlohmann::json error_reply(const std::string& msg) { return {{"ok", false}, {"error", msg}}; }

}  // namespace

std::string default_control_socket_path() {
  if (const char* x = std::getenv("XDG_RUNTIME_DIR"); x && *x) return std::string(x) + "/foveal/control.sock";
  return "/tmp/foveal-" + std::to_string(::getuid()) + "/control.sock";
}

Result<ControlServer> ControlServer::listen(const std::string& path) {
  auto addr = address(path);
  if (!addr) return addr.error();
  const auto dir = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!dir.empty()) {
    std::filesystem::create_directories(dir, ec);
    if (ec) return io_error(dir.string() + ": cannot create: " + ec.message());
    ::chmod(dir.c_str(), 0700);
  }
  // A socket file nobody answers on is left from a crash: replace it.
  if (std::filesystem::exists(path, ec)) {
    const int probe = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    const bool live = probe >= 0 && ::connect(probe, reinterpret_cast<const sockaddr*>(&*addr), sizeof *addr) == 0;
    if (probe >= 0) ::close(probe);
    if (live) return bad_input(path + ": another foveald is already listening there");
    ::unlink(path.c_str());
  }
  ControlServer s;
  s.path_ = path;
  s.listen_fd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (s.listen_fd_ < 0) return io_error(std::string("control socket: ") + std::strerror(errno));
  const mode_t old = ::umask(0177);  // the socket is born 0600
  const int rc = ::bind(s.listen_fd_, reinterpret_cast<const sockaddr*>(&*addr), sizeof *addr);
  ::umask(old);
  if (rc != 0) return io_error(path + ": cannot bind: " + std::strerror(errno));
  if (::listen(s.listen_fd_, 16) != 0) return io_error(path + ": cannot listen: " + std::strerror(errno));
  return s;
}

ControlServer::ControlServer(ControlServer&& o) noexcept
    : path_(std::move(o.path_)),
      listen_fd_(std::exchange(o.listen_fd_, -1)),
      clients_(std::move(o.clients_)),
      served_(o.served_),
      bad_(o.bad_) {
  o.clients_.clear();
}

ControlServer::~ControlServer() {
  for (Client& c : clients_) ::close(c.fd);
  if (listen_fd_ >= 0) {
    ::close(listen_fd_);
    ::unlink(path_.c_str());
  }
}

bool ControlServer::send_all(int fd, const std::string& data) {
  std::size_t off = 0;
  const TimeNs deadline = monotonic_now_ns() + 100 * kNsPerMs;  // a stuck reader must not stall us
  while (off < data.size()) {
    const ssize_t n = ::send(fd, data.data() + off, data.size() - off, MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n > 0) {
      off += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && (errno == EAGAIN || errno == EINTR) && monotonic_now_ns() < deadline) {
      pollfd p{fd, POLLOUT, 0};
      ::poll(&p, 1, 10);
      continue;
    }
    return false;
  }
  return true;
}

void ControlServer::handle_line(Client& c, const std::string& line, const Handler& handler) {
  nlohmann::json reply;
  nlohmann::json req = parse_json_or_discarded(line, {kMaxMessageBytes, kMaxJsonDepth});
  if (req.is_discarded() || !req.is_object()) {
    ++bad_;
    reply = error_reply("malformed request: expected one JSON object per line");
  } else {
    try {
      reply = handler(req);
    } catch (const std::exception& e) {  // a handler bug must not take the daemon down
      reply = error_reply(std::string("internal error: ") + e.what());
    }
    ++served_;
  }
  if (!send_all(c.fd, reply.dump() + "\n")) {
    ::close(c.fd);
    c.fd = -1;
  }
}

void ControlServer::poll(int timeout_ms, const Handler& handler) {
  std::vector<pollfd> fds;
  fds.push_back({listen_fd_, POLLIN, 0});
  for (const Client& c : clients_) fds.push_back({c.fd, POLLIN, 0});
  if (::poll(fds.data(), fds.size(), timeout_ms) <= 0) return;

  if (fds[0].revents & POLLIN) {
    for (;;) {
      const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
      if (fd < 0) break;
      if (clients_.size() >= kMaxClients) {
        send_all(fd, error_reply("too many clients").dump() + "\n");
        ::close(fd);
        continue;
      }
      clients_.push_back({fd, {}});
    }
  }
  for (std::size_t i = 1; i < fds.size(); ++i) {
    if (!(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
    Client& c = clients_[i - 1];
    char buf[4096];
    for (;;) {
      const ssize_t n = ::recv(c.fd, buf, sizeof buf, MSG_DONTWAIT);
      if (n > 0) {
        c.in.append(buf, static_cast<std::size_t>(n));
        std::size_t nl;
        while (c.fd >= 0 && (nl = c.in.find('\n')) != std::string::npos) {
          std::string line = c.in.substr(0, nl);
          c.in.erase(0, nl + 1);
          if (!line.empty() && line.back() == '\r') line.pop_back();
          if (line.size() > kMaxMessageBytes) {
            ++bad_;
            send_all(c.fd, error_reply("request longer than " + std::to_string(kMaxMessageBytes) + " bytes").dump() + "\n");
          } else if (!line.empty()) {
            handle_line(c, line, handler);
          }
        }
        if (c.fd >= 0 && c.in.size() > kMaxMessageBytes) {
          ++bad_;
          send_all(c.fd, error_reply("request longer than " + std::to_string(kMaxMessageBytes) + " bytes").dump() + "\n");
          ::close(c.fd);
          c.fd = -1;
        }
        if (c.fd < 0) break;
        continue;
      }
      if (n < 0 && errno == EINTR) continue;
      if (n < 0 && errno == EAGAIN) break;
      ::close(c.fd);  // 0: the client closed; < 0: it broke
      c.fd = -1;
      break;
    }
  }
  std::erase_if(clients_, [](const Client& c) { return c.fd < 0; });
}

Result<nlohmann::json> control_request(const std::string& path, const nlohmann::json& request, int timeout_ms) {
  auto addr = address(path);
  if (!addr) return addr.error();
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return io_error(std::string("socket: ") + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&*addr), sizeof *addr) != 0)
    return io_error(path + ": cannot connect (is foveald running?): " + std::strerror(errno));
  const std::string msg = request.dump() + "\n";
  if (::send(fd, msg.data(), msg.size(), MSG_NOSIGNAL) != static_cast<ssize_t>(msg.size()))
    return io_error(path + ": send failed");
  std::string in;
  const TimeNs deadline = monotonic_now_ns() + static_cast<TimeNs>(timeout_ms) * kNsPerMs;
  while (in.find('\n') == std::string::npos) {
    const TimeNs left = deadline - monotonic_now_ns();
    if (left <= 0) return io_error(path + ": no reply within " + std::to_string(timeout_ms) + " ms");
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(left / kNsPerMs) + 1) <= 0) continue;
    char buf[4096];
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) return io_error(path + ": connection closed before the reply");
    in.append(buf, static_cast<std::size_t>(n));
    if (in.size() > 16 * ControlServer::kMaxMessageBytes) return io_error(path + ": reply too long");
  }
  nlohmann::json reply = parse_json_or_discarded(in.substr(0, in.find('\n')), {16 * ControlServer::kMaxMessageBytes, kMaxJsonDepth});
  if (reply.is_discarded()) return io_error(path + ": malformed reply");
  return reply;
}

}  // namespace foveal

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "foveal/core/clock.hpp"
#include "foveal/core/json_file.hpp"
#include "foveal/runtime/control_server.hpp"

#include "socket_path.hpp"

namespace foveal {

Result<nlohmann::json> control_request(const std::string& path, const nlohmann::json& request, int timeout_ms) {
  auto addr = control_detail::socket_address(path);
  if (!addr) return addr.error();
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return io_error(std::string("socket: ") + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&*addr), sizeof *addr) != 0)
    return io_error(path + ": cannot connect (is foveald running?): " + std::strerror(errno));
  // Only this user's daemon (or root's) may answer: a socket another user planted on
  // the path would otherwise feed us its replies.
  ucred peer{};
  socklen_t len = sizeof peer;
  if (::getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &peer, &len) != 0)
    return io_error(path + ": cannot tell who serves the socket: " + std::strerror(errno));
  if (peer.uid != ::geteuid() && peer.uid != 0)
    return bad_input(path + ": served by uid " + std::to_string(peer.uid) + ", not by you (uid " +
                     std::to_string(::geteuid()) + "): not your foveald, refusing to talk to it");
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

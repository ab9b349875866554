#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "foveal/core/clock.hpp"
#include "foveal/core/json_file.hpp"
#include "foveal/core/json_text.hpp"
#include "foveal/runtime/control_server.hpp"

#include "socket_path.hpp"

namespace foveal {

namespace {

/// SO_SNDTIMEO for what is left until `deadline` (at least 1 ms: 0 would mean forever).
bool set_send_timeout(int fd, TimeNs deadline) {
  const TimeNs left = std::max<TimeNs>(deadline - monotonic_now_ns(), kNsPerMs);
  timeval tv{};
  tv.tv_sec = static_cast<time_t>(left / kNsPerSec);
  tv.tv_usec = static_cast<suseconds_t>((left % kNsPerSec) / 1000);
  return ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv) == 0;
}

/// connect() that gives up at `deadline`. A Unix stream connect waits while the
/// listener's backlog is full (a stopped foveald); Linux bounds that wait by SO_SNDTIMEO
/// and then fails with EAGAIN (a non-blocking connect fails at once, with no way to
/// poll for room). 0, or -1 with errno; EAGAIN: the deadline passed.
int connect_until(int fd, const sockaddr_un& addr, TimeNs deadline) {
  for (;;) {
    if (monotonic_now_ns() >= deadline) {
      errno = EAGAIN;
      return -1;
    }
    if (!set_send_timeout(fd, deadline)) return -1;
    if (::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0) return 0;
    if (errno != EINTR) return -1;
  }
}

/// The whole message sent by `deadline`; 0, or -1 with errno (EAGAIN: too late).
int send_until(int fd, const std::string& msg, TimeNs deadline) {
  std::size_t sent = 0;
  while (sent < msg.size()) {
    if (monotonic_now_ns() >= deadline || !set_send_timeout(fd, deadline)) {
      if (monotonic_now_ns() >= deadline) errno = EAGAIN;
      return -1;
    }
    const ssize_t n = ::send(fd, msg.data() + sent, msg.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno == EWOULDBLOCK) errno = EAGAIN;
    if (n < 0) return -1;
    sent += static_cast<std::size_t>(n);
  }
  return 0;
}

}  // namespace

Result<nlohmann::json> control_request(const std::string& path, const nlohmann::json& request, int timeout_ms) {
  auto addr = control_detail::socket_address(path);
  if (!addr) return addr.error();
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return io_error(std::string("socket: ") + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  // One deadline for connecting, sending and the reply: a stopped foveald can hold each.
  const TimeNs deadline = monotonic_now_ns() + static_cast<TimeNs>(std::max(timeout_ms, 0)) * kNsPerMs;
  if (connect_until(fd, *addr, deadline) != 0) {
    if (errno == EAGAIN)
      return io_error(path + ": not accepting connections within " + std::to_string(timeout_ms) +
                      " ms (foveald stopped or flooded?)");
    return io_error(path + ": cannot connect (is foveald running?): " + std::strerror(errno));
  }
  // Only this user's daemon (or root's) may answer: a socket another user planted on
  // the path would otherwise feed us its replies.
  ucred peer{};
  socklen_t len = sizeof peer;
  if (::getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &peer, &len) != 0)
    return io_error(path + ": cannot tell who serves the socket: " + std::strerror(errno));
  if (peer.uid != ::geteuid() && peer.uid != 0)
    return bad_input(path + ": served by uid " + std::to_string(peer.uid) + ", not by you (uid " +
                     std::to_string(::geteuid()) + "): not your foveald, refusing to talk to it");
  const std::string msg = json_text(request) + "\n";
  if (send_until(fd, msg, deadline) != 0) {
    if (errno == EAGAIN) return io_error(path + ": request not taken within " + std::to_string(timeout_ms) + " ms");
    return io_error(path + ": send failed: " + std::strerror(errno));
  }
  std::string in;
  while (in.find('\n') == std::string::npos) {
    const TimeNs left = deadline - monotonic_now_ns();
    if (left <= 0) return io_error(path + ": no reply within " + std::to_string(timeout_ms) + " ms");
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(std::min<TimeNs>(left / kNsPerMs + 1, 1 << 30))) <= 0) continue;
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

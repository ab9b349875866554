#pragma once
// The daemon's control socket: a Unix stream socket (mode 0600) speaking
// line-delimited JSON (docs/control.md). One request per line, one reply per request.
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/core/error.hpp"

namespace foveal {

/// Where the daemon listens by default: $XDG_RUNTIME_DIR/foveal/control.sock
/// (/tmp/foveal-<uid>/control.sock when XDG_RUNTIME_DIR is unset).
std::string default_control_socket_path();

/// Not thread-safe: one thread calls poll(). Requests are answered in order per client.
class ControlServer {
 public:
  static constexpr std::size_t kMaxMessageBytes = 64 * 1024;
  static constexpr std::size_t kMaxClients = 32;

  /// Turns one parsed request into its reply. Runs on the poll() thread.
  using Handler = std::function<nlohmann::json(const nlohmann::json& request)>;

  /// Creates the socket's directory (0700) and the socket (0600). A stale socket file
  /// (nobody listening) is replaced; a live one is an error ("already running").
  static Result<ControlServer> listen(const std::string& path);
  ControlServer(ControlServer&&) noexcept;
  ControlServer& operator=(ControlServer&&) = delete;
  ~ControlServer();

  /// Waits up to timeout_ms for activity, accepts clients, reads, and answers every
  /// complete line. Malformed JSON and oversized lines get an error reply; an oversized
  /// line's client is then disconnected. Never throws.
  void poll(int timeout_ms, const Handler& handler);

  const std::string& path() const { return path_; }
  std::size_t clients() const { return clients_.size(); }
  std::uint64_t requests_served() const { return served_; }
  std::uint64_t bad_requests() const { return bad_; }

 private:
  struct Client {
    int fd = -1;
    std::string in;
  };
  ControlServer() = default;
  void handle_line(Client& c, const std::string& line, const Handler& handler);
  static bool send_all(int fd, const std::string& data);

  std::string path_;
  int listen_fd_ = -1;
  std::vector<Client> clients_;
  std::uint64_t served_ = 0, bad_ = 0;
};

/// Client side: connects, sends one request, waits up to timeout_ms for its reply.
Result<nlohmann::json> control_request(const std::string& path, const nlohmann::json& request, int timeout_ms = 2000);

}  // namespace foveal

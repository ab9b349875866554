#pragma once
// The daemon's control socket: a Unix stream socket (mode 0600) speaking
// line-delimited JSON (docs/daemon.md, "Control socket"). One request per line, one reply per request.
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/core/clock.hpp"
#include "foveal/core/error.hpp"
#include "foveal/core/problem_throttle.hpp"

namespace foveal {

/// Where the daemon listens by default: $XDG_RUNTIME_DIR/foveal/control.sock
/// (/tmp/foveal-<uid>/control.sock when XDG_RUNTIME_DIR is unset).
std::string default_control_socket_path();
/// Where `foveal record --control` listens: record.sock beside the daemon's socket.
std::string default_record_socket_path();

/// Not thread-safe: one thread calls poll(). Requests are answered in order per client.
/// poll() never waits on a client: replies queue per client and go out when the socket
/// is writable; a client that lets them pile up past kMaxPendingReplyBytes is dropped.
class ControlServer {
 public:
  static constexpr std::size_t kMaxMessageBytes = 64 * 1024;
  static constexpr std::size_t kMaxClients = 32;
  /// Unread replies a client may have queued before it is dropped.
  static constexpr std::size_t kMaxPendingReplyBytes = 256 * 1024;
  /// Requests answered per client per poll(): a flooding client cannot starve the others.
  /// A client that leaves replies unread gets one per turn, after everyone else.
  static constexpr int kMaxRequestsPerTurn = 8;

  /// Turns one parsed request into its reply. Runs on the poll() thread. The request is
  /// an object whose "cmd" is a string.
  using Handler = std::function<nlohmann::json(const nlohmann::json& request)>;
  /// Where the server reports dropped clients (default: a warning on stderr).
  using Logger = std::function<void(const std::string& message)>;

  /// Creates the socket's directory (0700) or checks an existing one: a directory of
  /// this user, not a link, no group or other access; never chmods it. Then the socket
  /// (0600). Only a stale socket (nobody listening) at the path is replaced; a live one
  /// ("already running") or anything else there is refused, named.
  static Result<ControlServer> listen(const std::string& path);
  ControlServer(ControlServer&&) noexcept;
  ControlServer& operator=(ControlServer&&) = delete;
  ~ControlServer();

  void set_logger(Logger logger) { logger_ = std::move(logger); }

  /// Waits up to timeout_ms for activity (0 when requests are already waiting), then
  /// writes queued replies, reads, answers complete lines and accepts new clients.
  /// Malformed, blank, wrongly typed and oversized requests get an error reply; an
  /// unterminated oversized line's client is then disconnected. When kMaxClients are
  /// connected a newcomer replaces one that leaves its replies unread, else the one
  /// idle longest. Never throws, never blocks.
  void poll(int timeout_ms, const Handler& handler);

  const std::string& path() const { return path_; }
  /// On the poll() thread only; the counters below may be read from any thread.
  std::size_t clients() const { return clients_.size(); }
  std::uint64_t requests_served() const { return served_.load(std::memory_order_relaxed); }
  std::uint64_t bad_requests() const { return bad_.load(std::memory_order_relaxed); }
  /// Clients closed by the server: unread replies over the bound, or room for a newcomer.
  std::uint64_t clients_dropped() const { return dropped_.load(std::memory_order_relaxed); }

 private:
  struct Client {
    int fd = -1;
    std::uint64_t id = 0;
    std::string in, out;     ///< unparsed input; replies not yet sent
    int lines = 0;           ///< complete lines in `in`
    std::size_t out_sent = 0;  ///< bytes of `out` already written
    TimeNs last_active = 0;  ///< last byte received or sent
  };
  ControlServer() = default;
  void accept_clients();
  void read_and_answer(Client& c, const Handler& handler, int max_requests);
  nlohmann::json answer(const std::string& line, const Handler& handler);
  void queue_reply(Client& c, const nlohmann::json& reply);
  void flush(Client& c);
  void drop(Client& c, const std::string& why);
  void log(const std::string& message);

  std::string path_;
  int listen_fd_ = -1;
  std::vector<Client> clients_;
  std::uint64_t next_id_ = 1;
  bool work_waiting_ = false;  ///< a client has complete lines left for the next turn
  Logger logger_;
  ProblemThrottle drop_log_;
  std::atomic<std::uint64_t> served_{0}, bad_{0}, dropped_{0};
};

/// Client side: connects, sends one request and reads its reply, all within timeout_ms
/// (a stopped server's full backlog or unread socket counts against it too).
Result<nlohmann::json> control_request(const std::string& path, const nlohmann::json& request, int timeout_ms = 2000);

}  // namespace foveal

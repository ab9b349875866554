#include "foveal/runtime/control_server.hpp"

#include <errno.h>  // program_invocation_short_name
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <tuple>
#include <utility>

#include "foveal/core/clock.hpp"
#include "foveal/core/json_file.hpp"
#include "foveal/core/json_text.hpp"
#include "socket_path.hpp"

namespace foveal {

namespace {

nlohmann::json error_reply(const std::string& msg) { return {{"ok", false}, {"error", msg}}; }

std::string too_long() { return "request longer than " + std::to_string(ControlServer::kMaxMessageBytes) + " bytes"; }

/// "[json.exception.type_error.302] type must be string, but is number" -> the part
/// after the bracket: what a client can act on.
std::string json_error_text(const nlohmann::json::exception& e) {
  const std::string what = e.what();
  const auto close = what.find("] ");
  return close == std::string::npos ? what : what.substr(close + 2);
}

}  // namespace

Result<ControlServer> ControlServer::listen(const std::string& path) {
  auto addr = control_detail::socket_address(path);
  if (!addr) return addr.error();
  const std::string dir = std::filesystem::path(path).parent_path().string();
  if (Status s = control_detail::prepare_private_dir(dir.empty() ? "." : dir); !s) return s.error();
  if (Status s = control_detail::clear_stale_socket(path, *addr); !s) return s.error();
  ControlServer s;
  s.path_ = path;
  s.listen_fd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (s.listen_fd_ < 0) return io_error(std::string("control socket: ") + std::strerror(errno));
  const mode_t old = ::umask(0177);  // the socket is born 0600
  const int rc = ::bind(s.listen_fd_, reinterpret_cast<const sockaddr*>(&*addr), sizeof *addr);
  ::umask(old);
  if (rc != 0) {
    const int e = errno;
    ::close(std::exchange(s.listen_fd_, -1));  // not ours to unlink: bind made nothing
    return io_error(path + ": cannot bind: " + std::strerror(e));
  }
  if (::listen(s.listen_fd_, 64) != 0) return io_error(path + ": cannot listen: " + std::strerror(errno));
  return s;
}

ControlServer::ControlServer(ControlServer&& o) noexcept
    : path_(std::move(o.path_)),
      listen_fd_(std::exchange(o.listen_fd_, -1)),
      clients_(std::move(o.clients_)),
      next_id_(o.next_id_),
      work_waiting_(o.work_waiting_),
      logger_(std::move(o.logger_)),
      drop_log_(o.drop_log_),
      served_(o.served_.load()),
      bad_(o.bad_.load()),
      dropped_(o.dropped_.load()) {
  o.clients_.clear();
}

ControlServer::~ControlServer() {
  for (Client& c : clients_) ::close(c.fd);
  if (listen_fd_ >= 0) {
    ::close(listen_fd_);
    ::unlink(path_.c_str());
  }
}

void ControlServer::log(const std::string& message) {
  if (logger_) logger_(message);
  else std::fprintf(stderr, "%s: warn: control: %s\n", program_invocation_short_name, message.c_str());
}

void ControlServer::drop(Client& c, const std::string& why) {
  dropped_.fetch_add(1, std::memory_order_relaxed);
  if (drop_log_.count())
    log("dropped client " + std::to_string(c.id) + ": " + why + " (" + std::to_string(drop_log_.problems()) +
        " so far)");
  ::close(c.fd);
  c.fd = -1;
}

void ControlServer::flush(Client& c) {
  while (c.fd >= 0 && c.out_sent < c.out.size()) {
    const ssize_t n = ::send(c.fd, c.out.data() + c.out_sent, c.out.size() - c.out_sent, MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n > 0) {
      c.out_sent += static_cast<std::size_t>(n);
      c.last_active = monotonic_now_ns();
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) break;  // the rest waits for POLLOUT
    ::close(c.fd);  // the client went away
    c.fd = -1;
  }
  if (c.out_sent == c.out.size()) {
    c.out.clear();
    c.out_sent = 0;
  }
}

void ControlServer::queue_reply(Client& c, const nlohmann::json& reply) {
  if (c.fd < 0) return;
  const std::string line = json_text(reply) + "\n";
  if (c.out.size() - c.out_sent + line.size() > kMaxPendingReplyBytes)
    return drop(c, "more than " + std::to_string(kMaxPendingReplyBytes / 1024) +
                       " KiB of replies unread (the client does not read them)");
  if (c.out_sent > 0 && c.out_sent == c.out.size()) {
    c.out.clear();
    c.out_sent = 0;
  }
  c.out += line;
}

nlohmann::json ControlServer::answer(const std::string& line, const Handler& handler) {
  auto bad = [this](const std::string& msg) {
    bad_.fetch_add(1, std::memory_order_relaxed);
    return error_reply(msg);
  };
  if (line.find_first_not_of(" \t") == std::string::npos) return bad("empty request: expected one JSON object per line");
  const nlohmann::json req = parse_json_or_discarded(line, {kMaxMessageBytes, kMaxJsonDepth});
  if (req.is_discarded() || !req.is_object()) return bad("malformed request: expected one JSON object per line");
  const auto cmd = req.find("cmd");
  if (cmd == req.end()) return bad("bad request: no \"cmd\" (e.g. {\"cmd\":\"status\"})");
  if (!cmd->is_string()) return bad(std::string("bad request: \"cmd\" must be a string, not a ") + cmd->type_name());
  try {
    nlohmann::json reply = handler(req);
    served_.fetch_add(1, std::memory_order_relaxed);
    return reply;
  } catch (const nlohmann::json::exception& e) {  // a field of the request has the wrong type or is missing
    return bad("bad request: " + json_error_text(e));
  } catch (const std::exception& e) {  // a handler bug must not take the daemon down
    served_.fetch_add(1, std::memory_order_relaxed);
    return error_reply(std::string("internal error: ") + e.what());
  }
}

void ControlServer::read_and_answer(Client& c, const Handler& handler, int max_requests) {
  // Read only while fewer than a turn's requests wait: a flood stays in the kernel.
  char buf[16 * 1024];
  while (c.in.size() <= kMaxMessageBytes && c.lines < max_requests) {
    const ssize_t n = ::recv(c.fd, buf, sizeof buf, MSG_DONTWAIT);
    if (n > 0) {
      c.in.append(buf, static_cast<std::size_t>(n));
      c.lines += static_cast<int>(std::count(buf, buf + n, '\n'));
      c.last_active = monotonic_now_ns();
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) break;
    if (c.lines == 0) {  // closed (0) or broken, nothing left to answer
      ::close(c.fd);
      c.fd = -1;
      return;
    }
    break;  // closed after its last requests: answer them first, the next read sees the end
  }
  std::size_t start = 0;
  for (int answered = 0; c.fd >= 0 && answered < max_requests; ++answered) {
    const std::size_t nl = c.in.find('\n', start);
    if (nl == std::string::npos) break;
    std::size_t len = nl - start;
    if (len > 0 && c.in[start + len - 1] == '\r') --len;
    if (len > kMaxMessageBytes) {
      bad_.fetch_add(1, std::memory_order_relaxed);
      queue_reply(c, error_reply(too_long()));
    } else {
      queue_reply(c, answer(c.in.substr(start, len), handler));
    }
    start = nl + 1;
    --c.lines;
  }
  c.in.erase(0, start);
  if (c.fd < 0) return;
  if (c.lines > 0) {
    work_waiting_ = true;
  } else if (c.in.size() > kMaxMessageBytes) {  // no end of line in sight: refuse and hang up
    bad_.fetch_add(1, std::memory_order_relaxed);
    queue_reply(c, error_reply(too_long()));
    flush(c);
    if (c.fd >= 0) ::close(c.fd);
    c.fd = -1;
  }
}

void ControlServer::accept_clients() {
  // At most a table's worth per turn: a connect flood cannot keep the loop here.
  for (std::size_t i = 0; i < kMaxClients; ++i) {
    const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
    if (fd < 0) break;
    // Dropped clients stay in the table (fd -1) until poll() ends: its indices stay valid.
    const auto live = std::count_if(clients_.begin(), clients_.end(), [](const Client& c) { return c.fd >= 0; });
    if (static_cast<std::size_t>(live) >= kMaxClients) {  // make room: one that does not read, else the idlest
      auto rank = [](const Client& c) { return std::tuple(c.fd < 0, c.out.empty(), c.last_active); };
      auto victim = std::min_element(clients_.begin(), clients_.end(),
                                     [&](const Client& a, const Client& b) { return rank(a) < rank(b); });
      drop(*victim, std::string("the table of ") + std::to_string(kMaxClients) + " clients is full and it " +
                        (victim->out.empty() ? "was idle longest" : "does not read its replies"));
    }
    Client c;
    c.fd = fd;
    c.id = next_id_++;
    c.last_active = monotonic_now_ns();
    clients_.push_back(std::move(c));
  }
}

void ControlServer::poll(int timeout_ms, const Handler& handler) {
  std::vector<pollfd> fds;
  fds.reserve(clients_.size() + 1);
  for (const Client& c : clients_) fds.push_back({c.fd, static_cast<short>(POLLIN | (c.out.empty() ? 0 : POLLOUT)), 0});
  fds.push_back({listen_fd_, POLLIN, 0});
  const bool waiting = std::exchange(work_waiting_, false);
  if (::poll(fds.data(), fds.size(), waiting ? 0 : timeout_ms) < 0 && !waiting) return;

  const std::size_t polled = clients_.size();
  std::vector<bool> done(polled);
  for (std::size_t i = 0; i < polled; ++i) {
    if (fds[i].revents & POLLOUT) flush(clients_[i]);
    // Clients that hung up: their last requests are answered (a `set` sent without
    // waiting still counts) and their places freed before newcomers need them.
    if (clients_[i].fd >= 0 && (fds[i].revents & (POLLHUP | POLLERR))) {
      read_and_answer(clients_[i], handler, kMaxRequestsPerTurn);
      done[i] = true;
    }
  }
  // Newcomers are read at once (`ctl` sends right after connecting). Clients that read
  // their replies go first; those that leave them unread get one request each, last.
  if (fds.back().revents & POLLIN) accept_clients();
  done.resize(clients_.size());
  std::vector<bool> unread(clients_.size());
  for (std::size_t i = 0; i < clients_.size(); ++i) unread[i] = !clients_[i].out.empty();
  for (const bool slow : {false, true})
    for (std::size_t i = 0; i < clients_.size(); ++i) {
      Client& c = clients_[i];
      if (c.fd < 0 || done[i] || unread[i] != slow) continue;
      const bool ready = i >= polled || (fds[i].revents & (POLLIN | POLLHUP | POLLERR));
      if (ready || c.lines > 0) read_and_answer(c, handler, slow ? 1 : kMaxRequestsPerTurn);
      // Most replies leave at once; a client whose socket was full waits for POLLOUT.
      if (c.fd >= 0 && !slow && !c.out.empty()) flush(c);
    }
  std::erase_if(clients_, [](const Client& c) { return c.fd < 0; });
}

}  // namespace foveal

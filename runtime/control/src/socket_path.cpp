#include "socket_path.hpp"

#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "foveal/core/file_mode.hpp"
#include "foveal/runtime/control_server.hpp"

namespace foveal {

std::string default_control_socket_path() {
  if (const char* x = std::getenv("XDG_RUNTIME_DIR"); x && *x) return std::string(x) + "/foveal/control.sock";
  return "/tmp/foveal-" + std::to_string(::getuid()) + "/control.sock";
}

std::string default_record_socket_path() {
  std::string p = default_control_socket_path();
  return p.substr(0, p.rfind('/') + 1) + "record.sock";
}

namespace control_detail {

namespace {

Status check_private_dir(const std::string& dir, const struct stat& st) {
  const std::string rule = "; the control socket needs a directory of yours that nobody else can enter "
                           "(mode 0700), or another --control path";
  if (S_ISLNK(st.st_mode)) return bad_input(dir + ": is a symbolic link" + rule);
  if (!S_ISDIR(st.st_mode)) return bad_input(dir + ": is not a directory" + rule);
  if (st.st_uid != ::geteuid())
    return bad_input(dir + ": belongs to uid " + std::to_string(st.st_uid) + ", not to you (uid " +
                     std::to_string(::geteuid()) + ")" + rule);
  if ((st.st_mode & 077) != 0)
    return bad_input(dir + ": has mode " + mode_text(st.st_mode) + ", open to group or others" + rule);
  return {};
}

}  // namespace

Result<sockaddr_un> socket_address(const std::string& path) {
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  if (path.size() >= sizeof addr.sun_path) return bad_input(path + ": socket path too long");
  std::memcpy(addr.sun_path, path.c_str(), path.size() + 1);
  return addr;
}

Status prepare_private_dir(const std::string& dir) {
  struct stat st{};
  if (::lstat(dir.c_str(), &st) == 0) return check_private_dir(dir, st);
  if (errno != ENOENT) return io_error(dir + ": cannot inspect: " + std::strerror(errno));
  // Missing: create it and any missing parents, each 0700 (a parent that exists is the
  // user's choice; only the socket's own directory must be private).
  const auto slash = dir.find_last_of('/');
  if (slash != std::string::npos && slash > 0) {
    const std::string parent = dir.substr(0, slash);
    if (::access(parent.c_str(), F_OK) != 0)
      if (Status s = prepare_private_dir(parent); !s) return s;
  }
  if (::mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST)
    return io_error(dir + ": cannot create: " + std::strerror(errno));
  // Whoever made it (us, or someone racing us), it must pass the same check.
  if (::lstat(dir.c_str(), &st) != 0) return io_error(dir + ": cannot inspect: " + std::strerror(errno));
  return check_private_dir(dir, st);
}

Status clear_stale_socket(const std::string& path, const sockaddr_un& addr) {
  struct stat st{};
  if (::lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return {};
    return io_error(path + ": cannot inspect: " + std::strerror(errno));
  }
  if (!S_ISSOCK(st.st_mode))
    return bad_input(path + ": exists and is not a socket; foveald replaces only a stale socket of its own "
                            "(remove the file or choose another --control path)");
  // Non-blocking: a stopped foveald's full backlog answers EAGAIN at once (it is alive)
  // where a blocking probe would wait for it forever.
  const int probe = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  const bool live = probe >= 0 && (::connect(probe, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0 ||
                                   errno == EAGAIN);
  if (probe >= 0) ::close(probe);
  if (live) return bad_input(path + ": another foveald is already listening there");
  if (::unlink(path.c_str()) != 0 && errno != ENOENT)
    return io_error(path + ": cannot remove the stale socket: " + std::strerror(errno));
  return {};
}

}  // namespace control_detail
}  // namespace foveal

#include "foveal/core/read_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace foveal {

namespace {

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

std::string describe_bytes(std::size_t bytes) {
  if (bytes >= (1u << 20) && bytes % (1u << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  if (bytes >= (1u << 10) && bytes % (1u << 10) == 0) return std::to_string(bytes >> 10) + " KiB";
  return std::to_string(bytes) + " bytes";
}

Result<int> open_regular_file(const std::string& path, const std::string& what) {
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) return io_error(path + ": cannot open " + what + ": " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int e = errno;
    ::close(fd);
    return io_error(path + ": cannot open " + what + ": " + std::strerror(e));
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    return bad_input(path + ": " + what + " is " + kind_of(st.st_mode) + "; foveal reads only regular files");
  }
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  return fd;
}

Result<std::string> read_regular_file(const std::string& path, std::size_t max_bytes, const std::string& what) {
  auto fd = open_regular_file(path, what);
  if (!fd) return fd.error();
  struct stat st {};
  const bool have_size = ::fstat(*fd, &st) == 0;
  if (have_size && static_cast<std::uint64_t>(st.st_size) > max_bytes) {
    ::close(*fd);
    return bad_input(path + ": " + what + " is " + std::to_string(st.st_size) + " bytes, more than the " +
                     describe_bytes(max_bytes) + " foveal reads");
  }
  std::string out;
  out.resize(have_size ? static_cast<std::size_t>(st.st_size) : 0);
  std::size_t got = 0;
  for (;;) {
    if (got == out.size()) {
      if (out.size() > max_bytes) break;  // grew while we read: refused below
      out.resize(out.size() + 4096);
    }
    const ssize_t n = ::read(*fd, out.data() + got, out.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int e = errno;
      ::close(*fd);
      return io_error(path + ": cannot read " + what + ": " + std::strerror(e));
    }
    if (n == 0) break;
    got += static_cast<std::size_t>(n);
  }
  ::close(*fd);
  out.resize(got);
  if (out.size() > max_bytes)
    return bad_input(path + ": " + what + " is more than the " + describe_bytes(max_bytes) + " foveal reads");
  return out;
}

}  // namespace foveal

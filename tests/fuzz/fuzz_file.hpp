#pragma once
// Fuzz inputs for readers that take a path: the bytes go into an anonymous memory
// file, named through /proc/self/fd.
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <string>

namespace foveal::fuzz {

class MemFile {
 public:
  MemFile(const std::uint8_t* data, std::size_t size) : fd_(::memfd_create("foveal-fuzz", MFD_CLOEXEC)) {
    std::size_t off = 0;
    while (fd_ >= 0 && off < size) {
      const ssize_t n = ::write(fd_, data + off, size - off);
      if (n <= 0) break;
      off += static_cast<std::size_t>(n);
    }
  }
  ~MemFile() {
    if (fd_ >= 0) ::close(fd_);
  }
  std::string path() const { return "/proc/self/fd/" + std::to_string(fd_); }

 private:
  int fd_;
};

/// An output path that is thrown away (importers write their result somewhere).
inline std::string scratch_output() { return "/dev/shm/foveal-fuzz-out-" + std::to_string(::getpid()) + ".csv"; }

}  // namespace foveal::fuzz

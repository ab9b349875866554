#include "foveal/runtime/fovea_shm.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <new>
#include <utility>

namespace foveal {

std::string default_fovea_shm_name() { return "/foveal-fovea-" + std::to_string(::getuid()); }

Result<FoveaShm> FoveaShm::create(const std::string& name) {
  const int fd = ::shm_open(name.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
  if (fd < 0) return io_error("shared memory " + name + ": " + std::strerror(errno));
  if (::ftruncate(fd, sizeof(FoveaShmBlock)) != 0) {
    ::close(fd);
    return io_error("shared memory " + name + ": cannot size: " + std::strerror(errno));
  }
  void* p = ::mmap(nullptr, sizeof(FoveaShmBlock), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  ::close(fd);
  if (p == MAP_FAILED) return io_error("shared memory " + name + ": cannot map: " + std::strerror(errno));
  FoveaShm s;
  s.name_ = name;
  s.owner_ = true;
  s.block_ = new (p) FoveaShmBlock{FoveaShmBlock::kMagic, FoveaShmBlock::kVersion,
                                   static_cast<std::uint32_t>(sizeof(FoveaShmBlock)), 0, {}};
  return s;
}

Result<FoveaShm> FoveaShm::open(const std::string& name) {
  const int fd = ::shm_open(name.c_str(), O_RDWR | O_CLOEXEC, 0);
  if (fd < 0) return io_error("shared memory " + name + ": " + std::strerror(errno) + " (is foveald running?)");
  struct stat st{};
  if (::fstat(fd, &st) != 0 || static_cast<std::size_t>(st.st_size) < sizeof(FoveaShmBlock)) {
    ::close(fd);
    return bad_input("shared memory " + name + ": too small for a fovea block");
  }
  void* p = ::mmap(nullptr, sizeof(FoveaShmBlock), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  ::close(fd);
  if (p == MAP_FAILED) return io_error("shared memory " + name + ": cannot map: " + std::strerror(errno));
  auto* b = static_cast<FoveaShmBlock*>(p);
  if (b->magic != FoveaShmBlock::kMagic || b->version != FoveaShmBlock::kVersion || b->size != sizeof(FoveaShmBlock)) {
    ::munmap(p, sizeof(FoveaShmBlock));
    return Error{ErrorKind::unsupported, "shared memory " + name + ": not a version-1 fovea block"};
  }
  FoveaShm s;
  s.name_ = name;
  s.block_ = b;
  return s;
}

FoveaShm::FoveaShm(FoveaShm&& o) noexcept
    : name_(std::move(o.name_)), block_(std::exchange(o.block_, nullptr)), owner_(o.owner_), frames_(o.frames_) {}

FoveaShm::~FoveaShm() {
  if (!block_) return;
  ::munmap(block_, sizeof(FoveaShmBlock));
  if (owner_) ::shm_unlink(name_.c_str());
}

void FoveaShm::publish(const FoveaFrame& f, int eye_width, int eye_height) {
  FoveaShmPayload p{};
  p.t_ns = f.t_ns;
  p.eye_width = static_cast<std::uint32_t>(eye_width);
  p.eye_height = static_cast<std::uint32_t>(eye_height);
  for (int e = 0; e < 2; ++e) {
    p.x[e] = f.eyes[e].px.x;
    p.y[e] = f.eyes[e].px.y;
    p.confidence[e] = f.eyes[e].confidence;
    p.state[e] = static_cast<std::uint32_t>(f.eyes[e].state);
  }
  p.frame = ++frames_;
  block_->latest.store(p);
}

}  // namespace foveal

#include "foveal/runtime/fovea_shm.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <new>
#include <utility>

#include "foveal/core/clock.hpp"
#include "foveal/core/file_mode.hpp"

namespace foveal {

std::string default_fovea_shm_name() {
  // FOVEAL_SHM_NAME moves foveald and its clients together (foveal-client reads it too).
  if (const char* name = std::getenv("FOVEAL_SHM_NAME"); name && *name) return name;
  return "/foveal-fovea-" + std::to_string(::getuid());
}

namespace {

/// Opens the block for writing: a new one, or one a dead foveald of this user left.
/// Someone else's block (another owner, a wider mode, not a plain file) is refused:
/// publishing into it would hand them the live gaze, or let them forge it.
Result<int> open_for_writing(const std::string& name) {
  const std::string what = "shared memory " + name + " (/dev/shm" + name + ")";
  int fd = ::shm_open(name.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd >= 0) {
    ::fchmod(fd, 0600);  // exactly 0600 whatever the umask
  } else {
    if (errno != EEXIST) return io_error(what + ": " + std::strerror(errno));
    fd = ::shm_open(name.c_str(), O_RDWR | O_NOFOLLOW | O_CLOEXEC, 0);
    if (fd < 0) return io_error(what + ": exists and cannot be opened: " + std::strerror(errno) + "; remove it");
    struct stat st{};
    std::string wrong;
    if (::fstat(fd, &st) != 0) wrong = std::strerror(errno);
    else if (!S_ISREG(st.st_mode)) wrong = "it is not a plain shared-memory object";
    else if (st.st_uid != ::geteuid())
      wrong = "it belongs to uid " + std::to_string(st.st_uid) + ", not to you (uid " + std::to_string(::geteuid()) + ")";
    else if ((st.st_mode & 07777) != 0600) wrong = "its mode is " + mode_text(st.st_mode) + ", not 0600";
    if (!wrong.empty()) {
      ::close(fd);
      return bad_input(what + ": exists and is not foveald's: " + wrong + "; refusing to publish gaze into it");
    }
  }
  // The writer holds a lock for as long as it runs: a second foveald must not share the
  // block, while a crashed one's lock is gone with it and its block is reused.
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int e = errno;
    ::close(fd);
    if (e == EWOULDBLOCK) return bad_input(what + ": another foveald is publishing there");
    return io_error(what + ": cannot lock: " + std::strerror(e));
  }
  return fd;
}

}  // namespace

Result<FoveaShm> FoveaShm::create(const std::string& name) {
  auto opened = open_for_writing(name);
  if (!opened) return opened.error();
  const int fd = *opened;
  if (::ftruncate(fd, sizeof(FoveaShmBlock)) != 0) {
    ::close(fd);
    return io_error("shared memory " + name + ": cannot size: " + std::strerror(errno));
  }
  void* p = ::mmap(nullptr, sizeof(FoveaShmBlock), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  if (p == MAP_FAILED) {
    const int e = errno;
    ::close(fd);
    return io_error("shared memory " + name + ": cannot map: " + std::strerror(e));
  }
  FoveaShm s;
  s.name_ = name;
  s.lock_fd_ = fd;
  s.owner_ = true;
  // Everything before the magic: a reader that sees the magic sees a whole block.
  auto* b = static_cast<FoveaShmBlock*>(p);
  std::atomic_ref<std::uint32_t>(b->magic).store(0, std::memory_order_relaxed);
  b = new (p) FoveaShmBlock{0, FoveaShmBlock::kVersion, static_cast<std::uint32_t>(sizeof(FoveaShmBlock)), 0, {}, {},
                            monotonic_now_ns(), static_cast<std::uint32_t>(::getpid()), FOVEAL_SHM_WRITER_LIVE, {}, {}};
  std::atomic_ref<std::uint32_t>(b->magic).store(FoveaShmBlock::kMagic, std::memory_order_release);
  s.block_ = b;
  return s;
}

Result<FoveaShm> FoveaShm::open(const std::string& name) {
  const int fd = ::shm_open(name.c_str(), O_RDWR | O_CLOEXEC, 0);
  if (fd < 0) return io_error("shared memory " + name + ": " + std::strerror(errno) + " (is foveald running?)");
  struct stat st{};
  if (::fstat(fd, &st) != 0) {
    const int e = errno;
    ::close(fd);
    return io_error("shared memory " + name + ": " + std::strerror(e));
  }
  if ((st.st_mode & 077) != 0) {  // foveald makes it 0600: a wider block is someone else's bait
    ::close(fd);
    return bad_input("shared memory " + name + ": mode " + mode_text(st.st_mode) +
                     " lets other users write it; not a block of foveald's");
  }
  // The header first, read rather than mapped: a short or older block is named, not mapped past its end.
  std::uint32_t header[3] = {};
  const bool whole_header = ::pread(fd, header, sizeof header, 0) == static_cast<ssize_t>(sizeof header);
  // Later versions only append (fovea_shm_layout.h): any version from this one on reads.
  std::string wrong;
  if (!whole_header || header[0] != FoveaShmBlock::kMagic) wrong = "not a fovea block (no FOVA magic)";
  else if (header[1] < FoveaShmBlock::kVersion)
    wrong = "a version-" + std::to_string(header[1]) + " block (an older foveald); this reader needs version " +
            std::to_string(FoveaShmBlock::kVersion) + " or later";
  else if (header[2] < sizeof(FoveaShmBlock) || header[2] > static_cast<std::uint64_t>(st.st_size))
    wrong = "its size field (" + std::to_string(header[2]) + " bytes) does not fit a version-" + std::to_string(header[1]) + " block";
  if (!wrong.empty()) {
    ::close(fd);
    return Error{ErrorKind::unsupported, "shared memory " + name + ": " + wrong};
  }
  void* p = ::mmap(nullptr, sizeof(FoveaShmBlock), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  ::close(fd);
  if (p == MAP_FAILED) return io_error("shared memory " + name + ": cannot map: " + std::strerror(errno));
  auto* b = static_cast<FoveaShmBlock*>(p);
  FoveaShm s;
  s.name_ = name;
  s.block_ = b;
  return s;
}

FoveaShm::FoveaShm(FoveaShm&& o) noexcept
    : name_(std::move(o.name_)),
      block_(std::exchange(o.block_, nullptr)),
      lock_fd_(std::exchange(o.lock_fd_, -1)),
      owner_(o.owner_),
      frames_(o.frames_) {}

FoveaShm::~FoveaShm() {
  if (!block_) return;
  if (owner_) block_->writer_state.store(FOVEAL_SHM_WRITER_STOPPED, std::memory_order_release);  // readers: "foveald stopped"
  ::munmap(block_, sizeof(FoveaShmBlock));
  if (owner_) ::shm_unlink(name_.c_str());
  if (lock_fd_ >= 0) ::close(lock_fd_);  // after the unlink: no second writer takes the name in between
}

void FoveaShm::heartbeat() { block_->heartbeat_ns.store(monotonic_now_ns(), std::memory_order_release); }

void FoveaShm::publish_view(const DisplayModel& m) {
  FoveaShmView v{};
  for (int e = 0; e < 2; ++e) {
    const EyeFrustum& f = m.frustum[static_cast<std::size_t>(e)];
    v.tan_left[e] = f.tan_left;
    v.tan_right[e] = f.tan_right;
    v.tan_bottom[e] = f.tan_bottom;
    v.tan_top[e] = f.tan_top;
  }
  v.ipd_m = m.ipd_mm / 1000.0f;
  v.published = 1;
  block_->view.store(v);
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
  // The motion first: a reader that then reads this fovea finds its motion there already
  // (or a later one, which it does not pair with this fovea).
  FoveaShmMotion m{};
  for (int e = 0; e < 2; ++e) {
    const FoveaPoint& pt = f.eyes[e];
    m.velocity_x[e] = pt.velocity_px_s.x;
    m.velocity_y[e] = pt.velocity_px_s.y;
    m.lag_x[e] = pt.lag_px.x;
    m.lag_y[e] = pt.lag_px.y;
    m.predictable[e] = pt.predictable ? 1u : 0u;
  }
  m.frame = p.frame;
  block_->motion.store(m);
  block_->latest.store(p);
}

}  // namespace foveal

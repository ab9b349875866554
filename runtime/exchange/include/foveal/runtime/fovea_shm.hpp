#pragma once
// The fovea stream for other programs: a shared-memory block holding the latest
// per-eye fovea, published with a seqlock (layout and protocol: docs/fovea-shm.md).
#include <cstdint>
#include <string>

#include "foveal/core/error.hpp"
#include "foveal/runtime/fovea.hpp"
#include "foveal/runtime/seqlock.hpp"

namespace foveal {

/// The payload, version 1. Plain data with fixed-size fields; little-endian.
struct FoveaShmPayload {
  std::int64_t t_ns;          ///< CLOCK_MONOTONIC of the gaze sample
  std::uint32_t eye_width;    ///< viewport size the pixels refer to
  std::uint32_t eye_height;
  float x[2], y[2];           ///< per eye (0 left, 1 right): viewport pixels, origin top-left, y down
  float confidence[2];        ///< 0..1
  std::uint32_t state[2];     ///< FoveaState: 0 fixation, 1 saccade, 2 pursuit, 3 blink, 4 lost
  std::uint64_t frame;        ///< increments with every publish
};

/// The whole block: a header readers check, then the seqlock.
struct FoveaShmBlock {
  static constexpr std::uint32_t kMagic = 0x41564F46;  // "FOVA" little-endian
  static constexpr std::uint32_t kVersion = 1;
  std::uint32_t magic;
  std::uint32_t version;
  std::uint32_t size;  ///< sizeof(FoveaShmBlock)
  std::uint32_t reserved;
  SeqLock<FoveaShmPayload> latest;
};

/// Default name: "/foveal-fovea-<uid>" (a file in /dev/shm).
std::string default_fovea_shm_name();

/// Maps the block: the writer creates it (mode 0600), readers open it read-write
/// (a seqlock reader writes nothing, but needs the atomics mapped).
class FoveaShm {
 public:
  /// Creates the block with O_EXCL. A block already there is taken over only when it
  /// is this user's, mode 0600, and no live writer holds it (one a crashed foveald
  /// left); anything else is refused naming the block and what is wrong with it.
  static Result<FoveaShm> create(const std::string& name);
  /// Refuses a block that group or others may read or write: not one foveald made.
  static Result<FoveaShm> open(const std::string& name);
  FoveaShm(FoveaShm&&) noexcept;
  FoveaShm& operator=(FoveaShm&&) = delete;
  ~FoveaShm();

  /// Writer side (one thread). Wait-free.
  void publish(const FoveaFrame& f, int eye_width, int eye_height);
  /// Reader side; false if no complete value could be read.
  bool read(FoveaShmPayload& out) const { return block_->latest.load(out); }

 private:
  FoveaShm() = default;
  std::string name_;
  FoveaShmBlock* block_ = nullptr;
  int lock_fd_ = -1;  ///< the writer's descriptor, flock'd: marks the block as in use
  bool owner_ = false;
  std::uint64_t frames_ = 0;
};

}  // namespace foveal

#pragma once
// The fovea stream for other programs: a shared-memory block holding the latest
// per-eye fovea, published with a seqlock (layout and protocol: docs/fovea-shm.md).
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>

#include "foveal/core/display_model.hpp"
#include "foveal/core/error.hpp"
#include "foveal/runtime/fovea.hpp"
#include "foveal/runtime/fovea_shm_layout.h"
#include "foveal/runtime/seqlock.hpp"

namespace foveal {

/// The fovea payload (since version 1) and the settings payload (version 2): the
/// C layout that foveal-client reads too (fovea_shm_layout.h).
using FoveaShmPayload = foveal_shm_fovea;
using FoveaShmSettings = foveal_shm_settings;
using FoveaShmView = foveal_shm_view;
using FoveaShmMotion = foveal_shm_motion;

/// The whole block: a header readers check, the fovea seqlock (the gaze thread writes
/// it), the settings seqlock and the writer's liveness (the control thread writes them).
struct FoveaShmBlock {
  static constexpr std::uint32_t kMagic = FOVEAL_SHM_MAGIC;
  static constexpr std::uint32_t kVersion = FOVEAL_SHM_VERSION;
  std::uint32_t magic;
  std::uint32_t version;
  std::uint32_t size;  ///< sizeof(FoveaShmBlock)
  std::uint32_t reserved;
  SeqLock<FoveaShmPayload> latest;
  SeqLock<FoveaShmSettings> settings;
  std::atomic<std::int64_t> heartbeat_ns;  ///< CLOCK_MONOTONIC, refreshed every FOVEAL_SHM_HEARTBEAT_NS
  std::atomic<std::uint32_t> writer_pid;
  std::atomic<std::uint32_t> writer_state;  ///< FOVEAL_SHM_WRITER_LIVE, then _STOPPED
  SeqLock<FoveaShmView> view;  ///< version 3: the display model's frustums and IPD
  SeqLock<FoveaShmMotion> motion;  ///< version 4: the latest fovea's velocity, lag, predictability
};
static_assert(offsetof(FoveaShmBlock, latest) == FOVEAL_SHM_FOVEA_SEQ_OFFSET);
static_assert(offsetof(FoveaShmBlock, settings) == FOVEAL_SHM_SETTINGS_SEQ_OFFSET);
static_assert(offsetof(FoveaShmBlock, heartbeat_ns) == FOVEAL_SHM_HEARTBEAT_OFFSET);
static_assert(offsetof(FoveaShmBlock, writer_pid) == FOVEAL_SHM_WRITER_PID_OFFSET);
static_assert(offsetof(FoveaShmBlock, writer_state) == FOVEAL_SHM_WRITER_STATE_OFFSET);
static_assert(offsetof(FoveaShmBlock, view) == FOVEAL_SHM_VIEW_SEQ_OFFSET);
static_assert(offsetof(FoveaShmBlock, motion) == FOVEAL_SHM_MOTION_SEQ_OFFSET);
static_assert(sizeof(FoveaShmBlock) == FOVEAL_SHM_V4_SIZE);

/// Default name: $FOVEAL_SHM_NAME when set, else "/foveal-fovea-<uid>" (a file in /dev/shm).
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

  /// Writer side. Wait-free. publish() (the fovea and, just before it, its motion) from
  /// one thread (the gaze thread);
  /// publish_settings() and heartbeat() from one thread (the control thread).
  void publish(const FoveaFrame& f, int eye_width, int eye_height);
  void publish_settings(const FoveaShmSettings& s) { block_->settings.store(s); }
  /// What the pixels mean (version 3); once, before the first publish().
  void publish_view(const DisplayModel& m);
  /// Tells readers the writer is alive; call at least every FOVEAL_SHM_HEARTBEAT_NS.
  void heartbeat();

  /// Reader side; false if no complete value could be read.
  bool read(FoveaShmPayload& out) const { return block_->latest.load(out); }
  bool read_settings(FoveaShmSettings& out) const { return block_->settings.load(out); }
  bool read_view(FoveaShmView& out) const { return block_->view.load(out); }
  /// The motion of the fovea whose frame it names (out.frame); pair it with read()'s.
  bool read_motion(FoveaShmMotion& out) const { return block_->motion.load(out); }

 private:
  FoveaShm() = default;
  std::string name_;
  FoveaShmBlock* block_ = nullptr;
  int lock_fd_ = -1;  ///< the writer's descriptor, flock'd: marks the block as in use
  bool owner_ = false;
  std::uint64_t frames_ = 0;
};

}  // namespace foveal

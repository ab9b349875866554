#pragma once
// The gaze thread: driver -> mapper (filter pipeline) -> latest-fovea exchange.
// The render thread reads latest() and never blocks on the driver.
#include <atomic>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "foveal/core/gaze_source.hpp"
#include "foveal/runtime/fovea.hpp"
#include "foveal/runtime/latency_histogram.hpp"
#include "foveal/runtime/seqlock.hpp"

namespace foveal {

/// Where the gaze thread is: waiting for a device that is not there (yet), reading
/// samples, recovering from a device loss, or done.
enum class SourceState { waiting, streaming, reconnecting, ended, failed, stopped };
const char* source_state_name(SourceState s);

struct GazeLoopStats {
  SourceState state = SourceState::waiting;
  SourceInfo device;              ///< the source's info() after its last successful open
  std::string waiting_for;        ///< while waiting: why the last open failed
  std::uint64_t samples = 0;      ///< samples mapped and published
  std::uint64_t skipped = 0;      ///< samples read while paused
  std::uint64_t timeouts = 0;
  std::uint64_t disconnects = 0;
  std::uint64_t reconnects = 0;
  std::int64_t latency_p50_ns = 0;  ///< sample arrival -> visible in latest()
  std::int64_t latency_p99_ns = 0;
  std::int64_t latency_max_ns = 0;
  bool realtime = false;            ///< the gaze thread runs with SCHED_FIFO
  bool ended = false;               ///< the source is exhausted (replay without loop)
  bool failed = false;              ///< stopped on an error (last_error)
  std::string last_error;
};

/// Thread-safety: start/stop from one controlling thread; latest(), stats(),
/// set_paused() and set_mapper() from any thread.
class GazeLoop {
 public:
  using Mapper = std::function<FoveaFrame(const GazeSample&)>;
  /// Called on the gaze thread after each publish (e.g. to write a trace). Keep it short.
  using Observer = std::function<void(const GazeSample&, const FoveaFrame&)>;

  /// `source` must outlive the loop. It is opened and started already, or, with
  /// `wait_for_source`, the loop opens it itself, retrying until the device is there.
  GazeLoop(GazeSource& source, Mapper mapper, Observer observer = {}, bool wait_for_source = false);
  ~GazeLoop();
  GazeLoop(const GazeLoop&) = delete;
  GazeLoop& operator=(const GazeLoop&) = delete;

  /// Starts the gaze thread; with `rt_priority` > 0 it asks for SCHED_FIFO at that
  /// priority (needs CAP_SYS_NICE or an rtprio limit; stats().realtime says if it got it).
  void start(int rt_priority = 0);
  /// Asks the thread to stop and joins it (returns within ~50 ms).
  void stop();
  bool finished() const { return finished_.load(std::memory_order_acquire); }

  /// What latest() holds before the first sample and from a device loss until the next
  /// sample (no_gaze_fovea(): the centre); without it, a default FoveaFrame before the
  /// first sample and the last fovea through a loss. Before start() only.
  void set_no_gaze(const FoveaFrame& f);
  const SeqLock<FoveaFrame>& latest() const { return latest_; }
  GazeLoopStats stats() const;
  void set_paused(bool p) { paused_.store(p, std::memory_order_relaxed); }
  bool paused() const { return paused_.load(std::memory_order_relaxed); }
  /// Replaces the mapper (new filter settings); the gaze thread picks it up before its
  /// next sample.
  void set_mapper(Mapper m);

 private:
  void run();
  void publish_stats(bool force);
  bool reconnect();

  GazeSource& source_;
  Mapper mapper_;
  Observer observer_;
  SeqLock<FoveaFrame> latest_;
  std::thread thread_;
  std::atomic<bool> stop_{false}, paused_{false}, finished_{false};

  mutable std::mutex mutex_;  // guards stats_ and next_mapper_
  GazeLoopStats stats_;
  Mapper next_mapper_;
  std::atomic<bool> mapper_pending_{false};
  bool wait_for_source_ = false;
  std::optional<FoveaFrame> no_gaze_;  // set before start(), read by the gaze thread

  // Gaze-thread-only state.
  LatencyHistogram latency_;
  GazeLoopStats local_;
  TimeNs last_publish_ = 0;
  int rt_priority_ = 0;
};

}  // namespace foveal

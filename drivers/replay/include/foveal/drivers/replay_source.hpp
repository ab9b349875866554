#pragma once
// Replay driver: plays a native gaze log as if a tracker produced it.
#include <optional>
#include <string>

#include "foveal/core/gaze_log.hpp"
#include "foveal/core/gaze_source.hpp"
#include "foveal/core/pacer.hpp"

namespace foveal {

struct ReplayOptions {
  std::string path;
  double speed = 1.0;               ///< 1 real time, 0 as fast as possible
  bool loop = false;                ///< start over at the end (timestamps keep increasing)
  std::optional<double> start_s;    ///< skip samples before this time (s from the first sample)
  std::optional<double> end_s;      ///< stop after this time (s from the first sample)

  Status validate() const;
};

/// Streams the file (constant memory whatever its length) and re-bases timestamps onto
/// the runtime clock: a sample recorded at t is delivered at start + (t - t_first)/speed,
/// where start is the time of the first next() call.
/// Not thread-safe: one thread drives it.
class ReplaySource final : public GazeSource {
 public:
  explicit ReplaySource(ReplayOptions opts) : opts_(std::move(opts)), pacer_(opts_.speed) {}

  Status open() override;
  void close() override;
  Status start() override;
  void stop() override { started_ = false; }
  ReadResult next(std::chrono::nanoseconds timeout) override;
  SourceInfo info() const override;

  const GazeLogHeader* header() const { return reader_ ? &reader_->header() : nullptr; }
  std::uint64_t loops_completed() const { return loops_; }

 private:
  /// Reads the next sample inside the time window into pending_, handling loop/end.
  Result<bool> load_next();
  Status restart_pass();

  ReplayOptions opts_;
  Pacer pacer_;
  std::optional<GazeLogReader> reader_;
  bool started_ = false;
  bool anchored_ = false;  ///< the pacer's clock has started (at the first next())
  bool have_pending_ = false;
  bool ended_ = false;
  GazeSample pending_{};
  TimeNs log_t0_ = 0;          ///< first sample's time in the log
  TimeNs window_first_ = 0;    ///< first delivered sample's log time
  TimeNs window_last_ = 0;     ///< last delivered log time in this pass
  TimeNs loop_offset_ = 0;     ///< added to log time after each loop
  bool have_t0_ = false;
  std::uint64_t loops_ = 0;
};

}  // namespace foveal

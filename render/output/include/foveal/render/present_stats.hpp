#pragma once
// Frame pacing of an on-screen output: how many frames reached the screen and how many
// refreshes went by without a new one. Direct mode feeds the vblank counter of each
// page-flip event; GLFW offers only the time each swap returned, so there the count is
// estimated from the refresh period. Not thread-safe; one output owns one.
#include <cstdint>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

namespace foveal::render {

class PresentStats {
 public:
  /// `refresh_hz` of the output's mode; 0 when unknown (then only a vblank counter can
  /// tell missed refreshes).
  explicit PresentStats(double refresh_hz = 0);

  /// One frame on screen at `t_ns` (CLOCK_MONOTONIC), with the vblank counter where the
  /// driver gives one. A counter that does not advance (drivers that fake vblank events)
  /// falls back to the clock.
  void record(std::int64_t t_ns, std::optional<std::uint64_t> vblank = std::nullopt);

  std::uint64_t presented() const { return presented_; }
  /// The times recorded since the last call, oldest first (the gaze-to-photon record
  /// takes each frame's shown time from here).
  std::vector<std::int64_t> take_shown();
  /// The drivers' events carry no vblank counter that advances (bochs, other drivers
  /// without vblank interrupts fake the event at commit): known after two frames.
  bool fake_vblank() const { return fake_vblank_; }
  /// The last recorded time; nullopt before the first frame.
  std::optional<std::int64_t> last() const { return last_t_; }
  /// Refreshes between two presented frames that showed no new frame; nullopt when
  /// neither a vblank counter nor the refresh rate is known.
  std::optional<std::uint64_t> missed() const;
  double refresh_hz() const { return refresh_hz_; }

  /// {"presented", "missed", "refresh_hz", "missed_from": "vblank"|"clock"|null,
  ///  "interval_ms": {"median", "p99", "max"}} over the last 1024 intervals.
  nlohmann::json json() const;

 private:
  double refresh_hz_ = 0;
  std::uint64_t presented_ = 0, missed_vblank_ = 0, missed_clock_ = 0;
  std::uint64_t counted_vblank_ = 0, counted_clock_ = 0;  ///< intervals judged each way
  std::optional<std::int64_t> last_t_;
  std::optional<std::uint64_t> last_vblank_;
  std::vector<double> intervals_ms_;  ///< ring of the last 1024
  std::vector<std::int64_t> untaken_;  ///< take_shown()'s; bounded by kIntervals
  bool fake_vblank_ = false;
};

}  // namespace foveal::render

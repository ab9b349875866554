#pragma once
// When each frame starts (docs/latency.md, "Pacing"): `asap` starts it as soon as the
// last one was presented; `jit` (just in time) as late before a refresh as the recent
// frames' work allows, plus a margin that grows on a missed refresh and shrinks slowly
// while frames land, so the gaze is as young as possible when the frame is shown.
// Render thread only.
#include <cstdint>
#include <deque>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "foveal/core/clock.hpp"
#include "foveal/core/error.hpp"

namespace foveal::daemon {

enum class Pacing { asap, jit };
/// "asap" or "jit"; bad_input otherwise.
Result<Pacing> parse_pacing(const std::string& s);
const char* pacing_name(Pacing p);

struct FramePlan {
  TimeNs start_ns = 0;           ///< sleep until then, then render
  TimeNs display_target_ns = 0;  ///< the refresh the frame is for (prediction's horizon)
};

class FramePacer {
 public:
  /// `refresh_hz` > 0: the display's; the refresh grid's phase comes from shown frames.
  FramePacer(Pacing pacing, double refresh_hz);

  /// The next frame's plan, at `now`, after the last frame shown at `last_shown_ns`
  /// (nullopt before the first).
  FramePlan plan(TimeNs now, std::optional<TimeNs> last_shown_ns) const;
  /// A frame's outcome: it started at `start`, was ready to show at `ready` (rendered
  /// and copied to the display's buffer: Output::last_ready_ns), and was shown at
  /// `shown` for the refresh `target`.
  void shown(TimeNs start, TimeNs ready, TimeNs shown, TimeNs target);

  Pacing pacing() const { return pacing_; }
  double margin_ms() const { return static_cast<double>(margin_ns_) * 1e-6; }
  std::uint64_t misses() const { return misses_; }
  /// {"pacing", "refresh_hz", "margin_ms", "misses", "frames", "work_ms_max_recent"};
  /// the first frame (shader compilation) is in "frames" only.
  nlohmann::json json() const;

 private:
  TimeNs work_estimate() const;  ///< the longest of the last 16 frames' start → ready, the first frame apart
  Pacing pacing_;
  TimeNs period_ns_;
  TimeNs margin_ns_;
  std::deque<TimeNs> recent_work_;
  std::uint64_t frames_ = 0, misses_ = 0, hits_in_a_row_ = 0;
};

}  // namespace foveal::daemon

#pragma once
// Gaze to photon, per frame (docs/latency.md): the gaze sample a frame used, when the
// renderer latched it, when the GPU finished and when the frame was shown, all on
// CLOCK_MONOTONIC, and the parts they split into. Render thread only.
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "foveal/core/clock.hpp"
#include "foveal/runtime/latency_histogram.hpp"

namespace foveal::daemon {

struct FrameLatency {
  // The sample (0: no sample yet; the frame showed the centre).
  TimeNs sample_t_ns = 0;         ///< the sample's time on the runtime clock (the tracker's, mapped)
  TimeNs sample_device_t_ns = 0;  ///< on the tracker's own clock (a replay: the log row's t_ns)
  TimeNs arrival_ns = 0;          ///< when it reached the runtime
  // The frame.
  TimeNs start_ns = 0, latch_ns = 0, gpu_done_ns = 0, shown_ns = 0;
  TimeNs display_target_ns = 0;   ///< when the render loop expected it on screen (0: no target)

  bool has_sample() const { return sample_t_ns != 0 && arrival_ns != 0; }
  /// shown − sample: the sum of the four parts below, exactly.
  double gaze_to_photon_ms() const { return ms(shown_ns - sample_t_ns); }
  double tracker_to_host_ms() const { return ms(arrival_ns - sample_t_ns); }
  double host_to_latch_ms() const { return ms(latch_ns - arrival_ns); }
  double latch_to_gpu_ms() const { return ms(gpu_done_ns - latch_ns); }
  double gpu_to_shown_ms() const { return ms(shown_ns - gpu_done_ns); }

  /// frames.csv's columns (csv_header() names them), without the leading comma; the
  /// sample's and the parts' cells are empty for a frame without a sample.
  static const char* csv_header();
  std::string csv_cells() const;

 private:
  static double ms(TimeNs ns) { return static_cast<double>(ns) * 1e-6; }
};

/// Percentiles over a run of frames, in constant memory.
class LatencyStats {
 public:
  void add(const FrameLatency& f);
  /// {"frames", "gaze_to_photon_ms": {"p50","p95","p99","max"}, "parts_ms": {...}, "shown_clock"}.
  nlohmann::json json(const char* shown_clock) const;

 private:
  struct Part {
    LatencyHistogram h;
    std::uint64_t negative = 0;  ///< clocks that disagree (a mapped device time after arrival)
    void add(TimeNs ns);
    nlohmann::json json() const;
  };
  std::uint64_t frames_ = 0;
  Part total_, tracker_host_, host_latch_, latch_gpu_, gpu_shown_;
};

}  // namespace foveal::daemon

#pragma once
// Synthetic driver: a seeded, deterministic scanpath generator with ground truth.
#include <cstdint>
#include <string>

#include "foveal/core/gaze_source.hpp"
#include "foveal/core/pacer.hpp"

namespace foveal {

enum class GazeEvent : std::uint8_t { fixation = 0, saccade = 1, pursuit = 2, blink = 3 };
const char* gaze_event_name(GazeEvent e);

struct SyntheticOptions {
  std::uint64_t seed = 1;
  double rate_hz = 120.0;
  double duration_s = 60.0;          ///< 0 = endless
  double noise_deg = 0.5;            ///< RMS angular measurement noise per eye
  double drift_deg_per_s = 0.1;      ///< RMS fixational drift speed (micro-jitter)
  double fixation_ms_min = 150, fixation_ms_max = 600;
  double saccade_deg_min = 2, saccade_deg_max = 20;
  double field_deg = 20;             ///< targets stay within +/- this azimuth/elevation
  double pursuit_probability = 0.15; ///< share of events that are smooth pursuit
  double pursuit_deg_per_s_min = 5, pursuit_deg_per_s_max = 20;
  double blink_rate_hz = 0.25;       ///< mean blinks per second of fixation
  double blink_ms_min = 100, blink_ms_max = 150;
  double depth_m_min = 0.5, depth_m_max = 3.0;  ///< vergence: target distance
  double ipd_mm = 63.0;
  double speed = 0.0;                ///< pacing as GazeSource: 1 real time, 0 as fast as possible

  Status validate() const;
};

/// The true state behind one generated sample.
struct GazeTruth {
  TimeNs t_ns = 0;  ///< same time base as the sample it belongs to
  GazeEvent event = GazeEvent::fixation;
  double azimuth_deg = 0;    ///< cyclopean gaze; + right
  double elevation_deg = 0;  ///< + up
  double depth_m = 1;
  std::array<glm::vec3, 2> direction{};  ///< true per-eye directions (vergence included)
  std::uint32_t event_index = 0;         ///< increments at every new event
};

/// Generates samples on the fly: same options -> bit-identical samples and truth, on
/// any machine (own Gaussian sampler, no std distributions). Saccades follow the main
/// sequence (duration = 2.2 ms/deg * A + 21 ms, minimum-jerk profile); a sample is
/// labelled saccade while the true speed exceeds 30 deg/s (the I-VT convention).
class SyntheticGenerator {
 public:
  explicit SyntheticGenerator(const SyntheticOptions& opts);
  /// Produces the next sample and its truth; false when duration_s has elapsed.
  bool next(GazeSample& sample, GazeTruth& truth);
  std::uint64_t index() const { return index_; }

 private:
  double uniform();   // [0,1)
  double gaussian();  // N(0,1)
  void begin_event();
  glm::vec3 eye_direction(int eye, double az_deg, double el_deg, double depth_m) const;

  SyntheticOptions o_;
  std::uint64_t rng_state_;
  bool has_spare_ = false;
  double spare_ = 0;
  std::uint64_t index_ = 0;
  std::uint32_t event_index_ = 0;

  // Current event.
  GazeEvent event_ = GazeEvent::fixation;
  double event_t0_ = 0, event_len_s_ = 0;
  double from_az_ = 0, from_el_ = 0, to_az_ = 0, to_el_ = 0;
  double vel_az_ = 0, vel_el_ = 0;       // pursuit, deg/s
  double drift_az_ = 0, drift_el_ = 0;   // fixational drift offset
  double depth_m_ = 1.0;
  double blink_start_s_ = 0, blink_end_s_ = -1;  // a blink inside the fixation
  double az_ = 0, el_ = 0;               // current true gaze
};

/// The generator as a GazeSource, paced like replay. Truth of the last sample is kept.
class SyntheticSource final : public GazeSource {
 public:
  explicit SyntheticSource(SyntheticOptions opts) : opts_(opts), gen_(opts), pacer_(opts.speed) {}
  Status open() override { return opts_.validate(); }
  void close() override {}
  Status start() override;
  void stop() override { started_ = false; }
  ReadResult next(std::chrono::nanoseconds timeout) override;
  SourceInfo info() const override;
  const GazeTruth& last_truth() const { return truth_; }

 private:
  SyntheticOptions opts_;
  SyntheticGenerator gen_;
  Pacer pacer_;
  bool started_ = false, have_pending_ = false;
  GazeSample pending_{};
  GazeTruth pending_truth_{}, truth_{};
};

}  // namespace foveal

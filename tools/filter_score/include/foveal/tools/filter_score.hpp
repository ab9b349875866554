#pragma once
// Runs the gaze pipeline over a synthetic scanpath and scores it against the ground
// truth: used by the acceptance tests and by `foveal filter-chart`.
#include <cmath>
#include <numbers>
#include <vector>

#include "foveal/drivers/synthetic_source.hpp"
#include "foveal/runtime/gaze_pipeline.hpp"

namespace foveal {

struct FilterScore {
  double raw_fixation_rms_deg = 0;       ///< raw error in settled fixations
  double filtered_fixation_rms_deg = 0;  ///< pipeline error in settled fixations
  double onset_precision = 0, onset_recall = 0, onset_f1 = 0;
  double mean_fixation_lag_ms = 0;       ///< fixation start -> output within 1 deg of truth
  double landing_within_1deg = 0;        ///< share of saccades landed within 1 deg one sample after the end
  double pursuit_lag_ms = 0;             ///< in pursuit: mean error / target speed (how far behind)
  int saccades = 0;
  bool any_nan = false;
};

inline double angle_deg(double az1, double el1, double az2, double el2) {
  return std::hypot((az1 - az2) * std::cos(el1 * std::numbers::pi / 180.0), el1 - el2);
}

inline void true_angles(const glm::vec3& d, double& az, double& el) {
  az = std::atan2(static_cast<double>(d.x), -static_cast<double>(d.z)) * 180.0 / std::numbers::pi;
  el = std::atan2(static_cast<double>(d.y), std::hypot(static_cast<double>(d.x), static_cast<double>(d.z))) * 180.0 / std::numbers::pi;
}

/// Scores the left eye's output. `settle_ms`: fixation samples this soon after a
/// fixation starts are left out of the jitter figure (they measure settling, not jitter).
/// `raw`: score the unfiltered samples instead (the "no filter" reference).
inline FilterScore score_pipeline(const SyntheticOptions& opts, const FilterConfig& cfg, double settle_ms = 50.0,
                                  bool raw = false) {
  SyntheticGenerator gen(opts);
  GazePipeline pipe(DisplayModel::vive_pro_eye(), cfg);
  struct Row {
    GazeEvent label;
    double t_az, t_el, r_az, r_el, o_az, o_el;
    bool raw_valid;
  };
  std::vector<Row> rows;
  std::vector<std::size_t> detected;  // onset sample indices
  GazeSample s;
  GazeTruth truth;
  FilterScore sc;
  while (gen.next(s, truth)) {
    const FoveaFrame f = pipe.update(s);
    const EyeEvents& ev = pipe.events(Eye::left);
    Row r{};
    r.label = truth.event;
    true_angles(truth.direction[0], r.t_az, r.t_el);
    r.raw_valid = s.eyes[0].has(kValidDirection);
    if (r.raw_valid) true_angles(s.eyes[0].direction, r.r_az, r.r_el);
    true_angles(ev.direction(), r.o_az, r.o_el);
    if (raw && r.raw_valid) {
      r.o_az = r.r_az;
      r.o_el = r.r_el;
    }
    if (!std::isfinite(f.eyes[0].px.x) || !std::isfinite(f.eyes[0].px.y)) sc.any_nan = true;
    if (ev.saccade_onset) {
      const double period = 1e9 / opts.rate_hz;
      detected.push_back(static_cast<std::size_t>(std::llround(static_cast<double>(ev.onset_t_ns) / period)));
    }
    rows.push_back(r);
  }
  // Truth onsets and ends.
  std::vector<std::size_t> onsets, ends;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    if (rows[i].label == GazeEvent::saccade && rows[i - 1].label != GazeEvent::saccade) onsets.push_back(i);
    if (rows[i - 1].label == GazeEvent::saccade && rows[i].label != GazeEvent::saccade) ends.push_back(i - 1);
  }
  sc.saccades = static_cast<int>(onsets.size());
  std::size_t tp = 0;
  std::vector<bool> used(detected.size(), false);
  for (std::size_t on : onsets)
    for (std::size_t k = 0; k < detected.size(); ++k)
      if (!used[k] && (detected[k] + 1 >= on) && detected[k] <= on + 1) {
        used[k] = true;
        ++tp;
        break;
      }
  sc.onset_precision = detected.empty() ? 0 : static_cast<double>(tp) / static_cast<double>(detected.size());
  sc.onset_recall = onsets.empty() ? 0 : static_cast<double>(tp) / static_cast<double>(onsets.size());
  sc.onset_f1 = sc.onset_precision + sc.onset_recall > 0
                    ? 2 * sc.onset_precision * sc.onset_recall / (sc.onset_precision + sc.onset_recall) : 0;
  // Landing: one sample after each saccade's last sample.
  int landed = 0, counted = 0;
  for (std::size_t e : ends)
    if (e + 1 < rows.size() && rows[e + 1].label == GazeEvent::fixation) {
      ++counted;
      landed += angle_deg(rows[e + 1].o_az, rows[e + 1].o_el, rows[e + 1].t_az, rows[e + 1].t_el) <= 1.0;
    }
  sc.landing_within_1deg = counted ? static_cast<double>(landed) / counted : 0;
  // Jitter in settled fixations and lag at fixation start.
  const auto settle = static_cast<std::size_t>(std::ceil(settle_ms * 1e-3 * opts.rate_hz));
  double raw2 = 0, out2 = 0, lag_sum = 0;
  std::size_t n = 0, fixations = 0;
  std::size_t run = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    if (r.label != GazeEvent::fixation) {
      run = 0;
      continue;
    }
    if (run == 0 && i > 0 && rows[i - 1].label == GazeEvent::saccade) {
      // Lag: samples until the output is within 1 deg of the truth.
      std::size_t k = i;
      while (k < rows.size() && rows[k].label == GazeEvent::fixation &&
             angle_deg(rows[k].o_az, rows[k].o_el, rows[k].t_az, rows[k].t_el) > 1.0)
        ++k;
      lag_sum += static_cast<double>(k - i) * 1000.0 / opts.rate_hz;
      ++fixations;
    }
    ++run;
    if (run <= settle || !r.raw_valid) continue;
    raw2 += std::pow(angle_deg(r.r_az, r.r_el, r.t_az, r.t_el), 2);
    out2 += std::pow(angle_deg(r.o_az, r.o_el, r.t_az, r.t_el), 2);
    ++n;
  }
  sc.raw_fixation_rms_deg = n ? std::sqrt(raw2 / static_cast<double>(n)) : 0;
  sc.filtered_fixation_rms_deg = n ? std::sqrt(out2 / static_cast<double>(n)) : 0;
  sc.mean_fixation_lag_ms = fixations ? lag_sum / static_cast<double>(fixations) : 0;
  // Pursuit lag: error along the motion over the target's speed, where the speed is known.
  double lag_ms = 0;
  std::size_t lag_n = 0;
  for (std::size_t i = 3; i < rows.size(); ++i) {
    if (rows[i].label != GazeEvent::pursuit || rows[i - 3].label != GazeEvent::pursuit) continue;
    const double vaz = (rows[i].t_az - rows[i - 1].t_az) * opts.rate_hz, vel = (rows[i].t_el - rows[i - 1].t_el) * opts.rate_hz;
    const double speed = std::hypot(vaz, vel);
    if (speed < 1.0) continue;
    // Positive when the output trails the target.
    const double along = ((rows[i].t_az - rows[i].o_az) * vaz + (rows[i].t_el - rows[i].o_el) * vel) / speed;
    lag_ms += along / speed * 1000.0;
    ++lag_n;
  }
  sc.pursuit_lag_ms = lag_n ? lag_ms / static_cast<double>(lag_n) : 0;
  return sc;
}

}  // namespace foveal

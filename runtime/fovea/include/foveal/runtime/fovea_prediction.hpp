#pragma once
// Prediction to display time: the renderer, at its latch, moves each eye's fovea from
// the time of its gaze sample to the time the frame is expected on the display
// (docs/filtering.md, "Prediction"; figures in docs/results/latency/prediction.md).
//
//   FoveaFrame shown = predict_fovea(latest, expected_display_t_ns, eye_w, eye_h, FoveaPrediction{});
//
// Semantics, per eye:
// - horizon h = display_t_ns - f.t_ns (both CLOCK_MONOTONIC, the runtime clock),
//   clamped to [0, max_horizon_ns]: a display time not after the sample predicts
//   nothing (the frame comes back unchanged); one further ahead than max_horizon_ns
//   predicts max_horizon_ns.
// - point.predictable (set by GazePipeline::update: fixation or smooth pursuit, smoothed
//   by the 1€ on the eye's own sample): px + lag_px + velocity_px_s * h, clamped inside
//   the viewport [0, eye_w) x [0, eye_h) as every FoveaPoint is. lag_px is the 1€'s own
//   lag behind a steady pursuit (0 in a fixation), velocity_px_s the smoothed gaze's
//   velocity; both from the pipeline.
// - a saccade (predictable false): held at its sample, the raw gaze at t; the landing
//   is not predicted. A blink, a loss, an eye filled in from the other one, the first
//   sample after a snap: unchanged.
// - non-finite px, lag or velocity, or a result that is not finite: that eye
//   unchanged. eye_w or eye_h not positive: the whole frame unchanged.
// - `enabled = false` returns f unchanged: the off switch (foveald --predict off).
// Everything else is kept: t_ns, device_t_ns and arrival_ns still name the sample the
// point came from (the latency record traces it), and state, confidence, velocity.
// The default is on: closer to the gaze at display time than the filter alone at 11,
// 22 and 45 ms (p50; p95 equal or better), most in pursuit, on the Vive recordings and
// synthetic scanpaths; a little worse in fixation at 45 ms and at p99 on the Vive
// recordings at 45 ms (docs/results/latency/prediction.md).
// FilterConfig::predict_ms (an older fixed extrapolation inside the pipeline, 0 by
// default) would be added on top: leave it at 0 with this on.
// Pure: no state, safe from any thread.
#include "foveal/core/clock.hpp"
#include "foveal/runtime/fovea.hpp"

namespace foveal {

struct FoveaPrediction {
  bool enabled = true;  ///< the default: on (docs/results/latency/prediction.md)
  /// Longest extrapolation: measured to 45 ms; a velocity is not worth trusting much
  /// further (a saccade can start any time).
  TimeNs max_horizon_ns = 50 * kNsPerMs;
};

FoveaFrame predict_fovea(const FoveaFrame& f, TimeNs display_t_ns, int eye_w, int eye_h,
                         const FoveaPrediction& p = {});

}  // namespace foveal

#pragma once
// What the runtime hands the compositor: one fovea point per eye.
#include <array>
#include <cstdint>

#include <glm/vec2.hpp>

#include "foveal/core/clock.hpp"
#include "foveal/core/gaze_sample.hpp"

namespace foveal {

enum class FoveaState : std::uint8_t { fixation, saccade, pursuit, blink, lost };
const char* fovea_state_name(FoveaState s);

struct FoveaPoint {
  glm::vec2 px{0.0f};  ///< viewport pixel (origin top-left, y down), always inside the viewport
  FoveaState state = FoveaState::lost;
  float confidence = 0.0f;  ///< 0..1
  /// The gaze pipeline's velocity estimate for this eye (viewport px/s, y down) and its
  /// verdict on extrapolating it (predict_fovea, foveal/runtime/fovea_prediction.hpp):
  /// true in fixation and smooth pursuit on the eye's own valid sample; false in a
  /// saccade (the point is the raw gaze and is held), a blink, a loss, or an eye filled
  /// in from the other one. The velocity is 0 where predictable is false.
  glm::vec2 velocity_px_s{0.0f};
  /// How far px trails the gaze at t in a steady movement (px): the velocity times the
  /// smoother's own lag; 0 where predictable is false. predict_fovea adds it when asked.
  glm::vec2 lag_px{0.0f};
  bool predictable = false;
};

struct FoveaFrame {
  TimeNs t_ns = 0;  ///< time of the sample it came from (runtime clock)
  /// The same sample on the tracker's own clock (ReadResult::device_t_ns; 0 unknown) and
  /// when it reached the runtime (CLOCK_MONOTONIC): set by the gaze loop, for the
  /// gaze-to-photon breakdown (docs/latency.md).
  TimeNs device_t_ns = 0;
  TimeNs arrival_ns = 0;
  std::array<FoveaPoint, 2> eyes{};
  const FoveaPoint& eye(Eye e) const { return eyes[static_cast<std::size_t>(e)]; }
};

/// What the runtime shows when it has no gaze to show (before a tracker's first sample,
/// while a lost device is waited for): both eyes at the viewport centre, the optical
/// centre where the gaze pipeline also puts an eye it has lost, state lost, confidence 0,
/// no sample (times 0).
FoveaFrame no_gaze_fovea(int eye_width, int eye_height);

}  // namespace foveal

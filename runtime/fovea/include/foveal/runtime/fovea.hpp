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

}  // namespace foveal

#include "foveal/runtime/fovea.hpp"

#include <algorithm>
#include <cmath>

namespace foveal {

const char* fovea_state_name(FoveaState s) {
  switch (s) {
    case FoveaState::fixation: return "fixation";
    case FoveaState::saccade: return "saccade";
    case FoveaState::pursuit: return "pursuit";
    case FoveaState::blink: return "blink";
    case FoveaState::lost: return "lost";
  }
  return "?";
}

void RawFoveaMapper::reset() {
  for (FoveaPoint& p : last_.eyes) {
    p.px = {0.5f * static_cast<float>(model_.eye_width), 0.5f * static_cast<float>(model_.eye_height)};
    p.state = FoveaState::lost;
    p.confidence = 0.0f;
  }
}

FoveaFrame RawFoveaMapper::update(const GazeSample& s) {
  FoveaFrame out = last_;
  out.t_ns = s.t_ns;
  for (Eye e : kEyes) {
    const EyeSample& es = s.eye(e);
    FoveaPoint& p = out.eyes[static_cast<std::size_t>(e)];
    glm::vec2 px{NAN, NAN};
    if (es.has(kValidDirection)) px = model_.direction_to_pixel(e, es.direction);
    if (std::isfinite(px.x) && std::isfinite(px.y)) {
      // Clamp to the last pixel's far edge minus a hair so the point stays inside.
      p.px.x = std::clamp(px.x, 0.0f, std::nextafter(static_cast<float>(model_.eye_width), 0.0f));
      p.px.y = std::clamp(px.y, 0.0f, std::nextafter(static_cast<float>(model_.eye_height), 0.0f));
      p.state = FoveaState::fixation;
      p.confidence = 1.0f;
    } else {
      p.state = p.state == FoveaState::lost ? FoveaState::lost : FoveaState::blink;
      p.confidence = 0.0f;
    }
  }
  last_ = out;
  return out;
}

}  // namespace foveal

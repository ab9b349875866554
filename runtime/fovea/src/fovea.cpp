#include "foveal/runtime/fovea.hpp"

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

FoveaFrame no_gaze_fovea(int eye_width, int eye_height) {
  FoveaFrame f;
  for (FoveaPoint& p : f.eyes) {
    p.px = {0.5f * static_cast<float>(eye_width), 0.5f * static_cast<float>(eye_height)};
    p.state = FoveaState::lost;
    p.confidence = 0.0f;
  }
  return f;
}

}  // namespace foveal

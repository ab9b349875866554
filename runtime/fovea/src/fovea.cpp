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

}  // namespace foveal

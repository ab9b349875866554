// The extensions the layer serves, one row each (the row lives in the extension's file).
#include "served_extension.hpp"

namespace foveal::openxr {

const ServedExtension& served(Ext e) {
  static const ServedExtension* const kTable[kExtCount] = {
      &kEyeGazeInteraction,      // eye_gaze_interaction.cpp
      &kFbEyeTrackingSocial,     // eye_tracker_fb.cpp
      &kVarjoQuadViews,          // quad_views.cpp
      &kVarjoFoveatedRendering,  // foveated_rendering.cpp
  };
  return *kTable[static_cast<int>(e)];
}

}  // namespace foveal::openxr

// The app's own reading of the eye gaze (XR_EXT_eye_gaze_interaction) each frame: one
// pose action bound to /user/eyes_ext/input/gaze_ext/pose, synced before the views are
// located, and the time of the sample it came from (XrEyeGazeSampleTimeEXT).
#pragma once

#include <openxr/openxr.h>

#include <memory>

namespace example {

struct GazeReading {
  bool active = false;   ///< the action was active at the sync
  bool tracked = false;  ///< located with a valid orientation
  XrTime sample_time = 0;
  XrQuaternionf orientation{0, 0, 0, 1};
};

class GazeReader {
 public:
  /// Creates the action set and space and attaches them to `session`; null with a message
  /// on stderr when the runtime refuses any of it.
  static std::unique_ptr<GazeReader> create(XrInstance instance, XrSession session);
  ~GazeReader();
  GazeReader(const GazeReader&) = delete;
  GazeReader& operator=(const GazeReader&) = delete;

  /// xrSyncActions; call once per frame before xrLocateViews.
  bool sync();
  /// The gaze latched at the last sync, located in `base` at `time`.
  GazeReading read(XrSpace base, XrTime time) const;

 private:
  GazeReader() = default;
  XrSession session_ = XR_NULL_HANDLE;
  XrActionSet set_ = XR_NULL_HANDLE;
  XrAction action_ = XR_NULL_HANDLE;
  XrSpace space_ = XR_NULL_HANDLE;
};

}  // namespace example

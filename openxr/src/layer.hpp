#pragma once
// The layer's state: the next layer's functions, what the runtime can do, and the
// handles it serves gaze for. One instance at a time (OpenXR runtimes allow one per
// process in practice). Tables are fixed arrays of atomic slots: they change under a
// mutex when the app creates or destroys something, and are read on the per-frame
// paths without one.
#include <time.h>

#define XR_USE_TIMESPEC  // XR_KHR_convert_timespec_time's declarations
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include <array>
#include <cstddef>
#include <atomic>
#include <memory>
#include <mutex>

#include "foveal/openxr/fb_eye_tracking_social.h"
#include "gaze_feed.hpp"

namespace foveal::openxr {

constexpr const char* kLayerName = "XR_APILAYER_FOVEAL_gaze";

/// The next layer's (or the runtime's) entry points the layer calls.
struct Next {
  PFN_xrGetInstanceProcAddr GetInstanceProcAddr = nullptr;
  PFN_xrDestroyInstance DestroyInstance = nullptr;
  PFN_xrGetSystemProperties GetSystemProperties = nullptr;
  PFN_xrCreateSession CreateSession = nullptr;
  PFN_xrDestroySession DestroySession = nullptr;
  PFN_xrPollEvent PollEvent = nullptr;
  PFN_xrCreateReferenceSpace CreateReferenceSpace = nullptr;
  PFN_xrCreateActionSpace CreateActionSpace = nullptr;
  PFN_xrDestroySpace DestroySpace = nullptr;
  PFN_xrLocateSpace LocateSpace = nullptr;
  PFN_xrCreateActionSet CreateActionSet = nullptr;
  PFN_xrDestroyActionSet DestroyActionSet = nullptr;
  PFN_xrCreateAction CreateAction = nullptr;
  PFN_xrDestroyAction DestroyAction = nullptr;
  PFN_xrSuggestInteractionProfileBindings SuggestInteractionProfileBindings = nullptr;
  PFN_xrAttachSessionActionSets AttachSessionActionSets = nullptr;
  PFN_xrGetCurrentInteractionProfile GetCurrentInteractionProfile = nullptr;
  PFN_xrSyncActions SyncActions = nullptr;
  PFN_xrGetActionStatePose GetActionStatePose = nullptr;
  PFN_xrStringToPath StringToPath = nullptr;
  PFN_xrConvertTimespecTimeToTimeKHR ConvertTimespecTimeToTimeKHR = nullptr;  // null without the extension
  PFN_xrCreateEyeTrackerFB CreateEyeTrackerFB = nullptr;  // the runtime's, when it has the extension
  PFN_xrDestroyEyeTrackerFB DestroyEyeTrackerFB = nullptr;
  PFN_xrGetEyeGazesFB GetEyeGazesFB = nullptr;
};

/// Who answers gaze: FOVEAL_OPENXR_GAZE=auto (default: foveald's wherever the runtime
/// has no eye tracker), foveal (foveald's always), runtime (pass everything through).
enum class GazeMode { automatic, foveal, runtime };

// Each slot's `handle` is null while the slot is free; claim_slot() fills the slot and
// stores the handle last, so that a reader that finds the handle sees the whole slot.
struct ActionSlot {
  std::atomic<XrAction> handle{XR_NULL_HANDLE};
  XrActionSet set = XR_NULL_HANDLE;
  std::atomic<bool> gaze{false};        ///< bound to the eye-gaze profile's pose
  std::atomic<bool> set_active{false};  ///< its set was active in the last xrSyncActions
};

struct SpaceSlot {
  std::atomic<XrSpace> handle{XR_NULL_HANDLE};
  int action = -1;  ///< index into actions
  XrSession session = XR_NULL_HANDLE;
  XrPosef pose_in_action{};
};

struct SessionSlot {
  std::atomic<XrSession> handle{XR_NULL_HANDLE};
  XrSpace view = XR_NULL_HANDLE;  ///< the layer's own VIEW space: the head the gaze is relative to
  std::atomic<bool> focused{false};
  std::atomic<bool> gaze_active{false};  ///< latched by xrSyncActions
};

struct EyeTrackerSlot {
  std::atomic<XrSession> handle{XR_NULL_HANDLE};  ///< its session (the tracker's handle is the slot's address)
};

struct Layer {
  std::mutex mutex;  ///< held only while creating or destroying
  XrInstance instance = XR_NULL_HANDLE;
  Next next;
  GazeMode mode = GazeMode::automatic;
  bool app_ext = false, app_fb = false;          ///< what the app enabled
  bool runtime_ext = false, runtime_fb = false;  ///< what the runtime got enabled
  std::atomic<bool> serve_ext{false}, serve_fb{false};
  bool decided = false;
  bool attached = false;
  XrPath profile_path = XR_NULL_PATH, eyes_path = XR_NULL_PATH, gaze_pose_path = XR_NULL_PATH, gaze_path = XR_NULL_PATH;
  std::unique_ptr<GazeFeed> feed;
  std::array<ActionSlot, 64> actions;
  std::array<SpaceSlot, 64> spaces;
  std::array<SessionSlot, 4> sessions;
  std::array<EyeTrackerSlot, 4> trackers;
};

Layer& layer();
void log_line(const char* text);

/// Decides, once per instance, whether the layer serves each extension (the runtime's
/// own eye tracker wins in auto mode). Takes the mutex's lock.
void decide_serving(XrSystemId system);

/// The slot holding handle h, or null. Lock-free: the per-frame paths call it.
template <typename Slot, std::size_t N, typename H>
Slot* find_slot(std::array<Slot, N>& slots, H h) {
  if (h == XR_NULL_HANDLE) return nullptr;
  for (auto& slot : slots)
    if (slot.handle.load(std::memory_order_acquire) == h) return &slot;
  return nullptr;
}

/// Fills the first free slot with fill(slot) and publishes h in it; null when all are
/// taken. Under the layer's mutex.
template <typename Slot, std::size_t N, typename H, typename Fill>
Slot* claim_slot(std::array<Slot, N>& slots, H h, Fill fill) {
  for (auto& slot : slots) {
    if (slot.handle.load() != XR_NULL_HANDLE) continue;
    fill(slot);
    slot.handle.store(h, std::memory_order_release);
    return &slot;
  }
  return nullptr;
}

inline SessionSlot* find_session(XrSession s) { return find_slot(layer().sessions, s); }
inline ActionSlot* find_action(XrAction a) { return find_slot(layer().actions, a); }
inline SpaceSlot* find_space(XrSpace s) { return find_slot(layer().spaces, s); }

// The intercepted functions, by extension (eye_gaze_interaction.cpp, eye_tracker_fb.cpp).
XRAPI_ATTR XrResult XRAPI_CALL layer_xrCreateAction(XrActionSet, const XrActionCreateInfo*, XrAction*);
XRAPI_ATTR XrResult XRAPI_CALL layer_xrDestroyAction(XrAction);
XRAPI_ATTR XrResult XRAPI_CALL layer_xrDestroyActionSet(XrActionSet);
XRAPI_ATTR XrResult XRAPI_CALL layer_xrSuggestInteractionProfileBindings(XrInstance,
                                                                         const XrInteractionProfileSuggestedBinding*);
XRAPI_ATTR XrResult XRAPI_CALL layer_xrAttachSessionActionSets(XrSession, const XrSessionActionSetsAttachInfo*);
XRAPI_ATTR XrResult XRAPI_CALL layer_xrGetCurrentInteractionProfile(XrSession, XrPath, XrInteractionProfileState*);
XRAPI_ATTR XrResult XRAPI_CALL layer_xrSyncActions(XrSession, const XrActionsSyncInfo*);
XRAPI_ATTR XrResult XRAPI_CALL layer_xrGetActionStatePose(XrSession, const XrActionStateGetInfo*, XrActionStatePose*);
XRAPI_ATTR XrResult XRAPI_CALL layer_xrCreateActionSpace(XrSession, const XrActionSpaceCreateInfo*, XrSpace*);
XRAPI_ATTR XrResult XRAPI_CALL layer_xrDestroySpace(XrSpace);
XRAPI_ATTR XrResult XRAPI_CALL layer_xrLocateSpace(XrSpace, XrSpace, XrTime, XrSpaceLocation*);
XRAPI_ATTR XrResult XRAPI_CALL layer_xrCreateEyeTrackerFB(XrSession, const XrEyeTrackerCreateInfoFB*, XrEyeTrackerFB*);
XRAPI_ATTR XrResult XRAPI_CALL layer_xrDestroyEyeTrackerFB(XrEyeTrackerFB);
XRAPI_ATTR XrResult XRAPI_CALL layer_xrGetEyeGazesFB(XrEyeTrackerFB, const XrEyeGazesInfoFB*, XrEyeGazesFB*);

/// The head (the layer's VIEW space) located in `base` at `time` through the runtime.
XrResult locate_head(const SessionSlot& s, XrSpace base, XrTime time, XrSpaceLocation& head);

}  // namespace foveal::openxr

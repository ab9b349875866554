#pragma once
// The layer's state: the next layer's functions, what the runtime can do, and the
// handles it serves gaze and quad views for. One instance at a time (OpenXR runtimes
// allow one per process in practice). Tables are fixed arrays of atomic slots: they
// change under a mutex when the app creates or destroys something, and are read on the
// per-frame paths without one.
#include <time.h>

#define XR_USE_TIMESPEC  // XR_KHR_convert_timespec_time's declarations
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include <array>
#include <atomic>
#include <cstddef>
#include <memory>
#include <mutex>

#include "foveal/openxr/fb_eye_tracking_social.h"
#include "gaze_feed.hpp"
#include "layer_log.hpp"
#include "served_extension.hpp"

namespace foveal::openxr {

constexpr const char* kLayerName = "XR_APILAYER_FOVEAL_gaze";

/// The next layer's (or the runtime's) entry points the layer calls.
struct Next {
  PFN_xrGetInstanceProcAddr GetInstanceProcAddr = nullptr;
  PFN_xrDestroyInstance DestroyInstance = nullptr;
  PFN_xrGetSystemProperties GetSystemProperties = nullptr;
  PFN_xrCreateSession CreateSession = nullptr;
  PFN_xrDestroySession DestroySession = nullptr;
  PFN_xrBeginSession BeginSession = nullptr;
  PFN_xrPollEvent PollEvent = nullptr;
  PFN_xrCreateReferenceSpace CreateReferenceSpace = nullptr;
  PFN_xrEnumerateReferenceSpaces EnumerateReferenceSpaces = nullptr;
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
  PFN_xrEnumerateViewConfigurations EnumerateViewConfigurations = nullptr;
  PFN_xrGetViewConfigurationProperties GetViewConfigurationProperties = nullptr;
  PFN_xrEnumerateViewConfigurationViews EnumerateViewConfigurationViews = nullptr;
  PFN_xrLocateViews LocateViews = nullptr;
  PFN_xrEndFrame EndFrame = nullptr;
  PFN_xrCreateSwapchain CreateSwapchain = nullptr;
  PFN_xrDestroySwapchain DestroySwapchain = nullptr;
  PFN_xrEnumerateSwapchainImages EnumerateSwapchainImages = nullptr;
  PFN_xrAcquireSwapchainImage AcquireSwapchainImage = nullptr;
  PFN_xrWaitSwapchainImage WaitSwapchainImage = nullptr;
  PFN_xrReleaseSwapchainImage ReleaseSwapchainImage = nullptr;
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

/// An action set attached to a session: only these refuse new bindings (the
/// specification's rule is per action set, not per instance).
struct AttachedSetSlot {
  std::atomic<XrActionSet> handle{XR_NULL_HANDLE};
  XrSession session = XR_NULL_HANDLE;
};

struct SpaceSlot {
  std::atomic<XrSpace> handle{XR_NULL_HANDLE};
  int action = -1;  ///< index into actions; -1: a COMBINED_EYE_VARJO reference space
  XrSession session = XR_NULL_HANDLE;
  XrPosef pose_in_action{};
};

/// The gaze as xrSyncActions latched it: every locate until the next sync answers from
/// this one reading, so two locates in a frame never disagree with each other or with
/// the action state. A sequence lock: written by the syncing thread, read by any.
class LatchedGaze {
 public:
  void store(bool active, const GazeNow& g);
  bool load(GazeNow& g) const;  ///< false: no active gaze at the last sync

 private:
  static constexpr std::size_t kWords = (sizeof(GazeNow) + 7) / 8;
  mutable std::atomic<std::uint32_t> seq_{0};
  std::atomic<bool> active_{false};
  std::array<std::atomic<std::uint64_t>, kWords> words_{};  // the GazeNow, whole: gaze_at predicts from it
};

struct QuadSession;  // quad_session.hpp: the quad views of a session that asked for them
struct QuadSessionDeleter {
  void operator()(QuadSession* q) const;  // quad_views.cpp
};

struct SessionSlot {
  std::atomic<XrSession> handle{XR_NULL_HANDLE};
  XrSpace view = XR_NULL_HANDLE;  ///< the layer's own VIEW space: the head the gaze is relative to
  std::atomic<bool> focused{false};
  std::atomic<bool> gaze_active{false};  ///< latched by xrSyncActions
  /// The last sync held an active set with a gaze action: the app reads the gaze, so its
  /// inner views (quad_views.cpp) are placed on the same latched sample it sees.
  std::atomic<bool> app_reads_gaze{false};
  LatchedGaze latched;
  XrSystemId system = XR_NULL_SYSTEM_ID;
  std::unique_ptr<QuadSession, QuadSessionDeleter> quad;  ///< set at xrCreateSession where quad views are served
};

struct EyeTrackerSlot {
  std::atomic<XrSession> handle{XR_NULL_HANDLE};  ///< its session (the tracker's handle is the slot's address)
};

struct Layer {
  std::mutex mutex;  ///< held only while creating or destroying
  XrInstance instance = XR_NULL_HANDLE;
  Next next;
  GazeMode mode = GazeMode::automatic;
  bool app[kExtCount] = {};      ///< the app enabled it (and the layer is not in pass-through mode)
  bool runtime[kExtCount] = {};  ///< ... and the runtime has it too: enabled there as well
  std::atomic<bool> serve_ext{false}, serve_fb{false};
  bool decided = false;
  XrVersion api_version = 0;  ///< the apiVersion the runtime accepted for this instance
  bool instance_1_1 = false;  ///< ... is 1.1 (and quad views are wanted): the inset configuration is core
  XrPath profile_path = XR_NULL_PATH, eyes_path = XR_NULL_PATH, gaze_pose_path = XR_NULL_PATH, gaze_path = XR_NULL_PATH;
  std::unique_ptr<GazeFeed> feed;
  std::array<ActionSlot, 64> actions;
  std::array<AttachedSetSlot, 64> attached_sets;
  std::array<SpaceSlot, 64> spaces;
  std::array<SessionSlot, 4> sessions;
  std::array<EyeTrackerSlot, 4> trackers;

  bool app_has(Ext e) const { return app[static_cast<int>(e)]; }
  bool runtime_has(Ext e) const { return runtime[static_cast<int>(e)]; }
  bool app_gaze() const { return app_has(Ext::eye_gaze_interaction) || app_has(Ext::fb_eye_tracking_social); }
  /// Quad views served by the layer: asked for (or core in 1.1), not the runtime's own.
  bool quad_views() const { return (app_has(Ext::varjo_quad_views) && !runtime_has(Ext::varjo_quad_views)) || instance_1_1; }
  bool foveated_rendering() const {
    return quad_views() && app_has(Ext::varjo_foveated_rendering) && !runtime_has(Ext::varjo_foveated_rendering);
  }
};

Layer& layer();

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

/// The head (the layer's VIEW space) located in `base` at `time` through the runtime.
XrResult locate_head(const SessionSlot& s, XrSpace base, XrTime time, XrSpaceLocation& head);

/// The gaze of the app's reading: the latched one for the action system's spaces.
/// Locates of gaze action spaces and of COMBINED_EYE_VARJO spaces (eye_gaze_interaction.cpp,
/// foveated_rendering.cpp), chosen by the core xrLocateSpace.
XrResult locate_gaze_action_space(XrSpace space, XrSpace base, XrTime time, XrSpaceLocation* location,
                                  const SpaceSlot* sp, const SpaceSlot* bp);
XrResult locate_combined_eye_space(XrSpace space, XrSpace base, XrTime time, XrSpaceLocation* location,
                                   const SpaceSlot* sp, const SpaceSlot* bp);
bool is_gaze_action_space(const SpaceSlot* s);

/// Quad views' part of session creation and destruction (quad_views.cpp); under the mutex.
void quad_session_created(SessionSlot& slot, const XrSessionCreateInfo* info);
void quad_session_destroyed(SessionSlot& slot);

/// The system properties every served extension fills (layer.cpp's xrGetSystemProperties).
void fill_foveated_rendering_properties(XrBaseOutStructure* p);

}  // namespace foveal::openxr

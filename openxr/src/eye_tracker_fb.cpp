// XR_FB_eye_tracking_social: each eye's gaze pose, validity and confidence from
// foveald's per-eye fovea, at the eyes' positions in the head (half the IPD either
// side of the VIEW origin). docs/openxr.md.
#include "layer.hpp"
#include "pose_math.hpp"

namespace foveal::openxr {

XRAPI_ATTR XrResult XRAPI_CALL layer_xrCreateEyeTrackerFB(XrSession, const XrEyeTrackerCreateInfoFB*, XrEyeTrackerFB*);
XRAPI_ATTR XrResult XRAPI_CALL layer_xrDestroyEyeTrackerFB(XrEyeTrackerFB);
XRAPI_ATTR XrResult XRAPI_CALL layer_xrGetEyeGazesFB(XrEyeTrackerFB, const XrEyeGazesInfoFB*, XrEyeGazesFB*);

namespace {

bool serving() { return layer().serve_fb.load(std::memory_order_relaxed); }

EyeTrackerSlot* tracker_slot(XrEyeTrackerFB t) {
  for (auto& slot : layer().trackers)
    if (reinterpret_cast<XrEyeTrackerFB>(&slot) == t && slot.handle.load(std::memory_order_acquire) != XR_NULL_HANDLE)
      return &slot;
  return nullptr;
}

}  // namespace

XRAPI_ATTR XrResult XRAPI_CALL layer_xrCreateEyeTrackerFB(XrSession session, const XrEyeTrackerCreateInfoFB* info,
                                                          XrEyeTrackerFB* tracker) {
  Layer& l = layer();
  if (!serving()) {
    if (l.next.CreateEyeTrackerFB) return l.next.CreateEyeTrackerFB(session, info, tracker);
    return XR_ERROR_FEATURE_UNSUPPORTED;
  }
  if (!info || !tracker || info->type != XR_TYPE_EYE_TRACKER_CREATE_INFO_FB) return XR_ERROR_VALIDATION_FAILURE;
  if (!find_session(session)) return XR_ERROR_HANDLE_INVALID;
  std::lock_guard lock(l.mutex);
  EyeTrackerSlot* slot = claim_slot(l.trackers, session, [](EyeTrackerSlot&) {});
  if (!slot) return XR_ERROR_LIMIT_REACHED;
  *tracker = reinterpret_cast<XrEyeTrackerFB>(slot);  // the tracker's handle is its slot
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrDestroyEyeTrackerFB(XrEyeTrackerFB tracker) {
  Layer& l = layer();
  if (!serving()) return l.next.DestroyEyeTrackerFB ? l.next.DestroyEyeTrackerFB(tracker) : XR_ERROR_HANDLE_INVALID;
  std::lock_guard lock(l.mutex);
  EyeTrackerSlot* slot = tracker_slot(tracker);
  if (!slot) return XR_ERROR_HANDLE_INVALID;
  slot->handle.store(XR_NULL_HANDLE);
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrGetEyeGazesFB(XrEyeTrackerFB tracker, const XrEyeGazesInfoFB* info,
                                                     XrEyeGazesFB* gazes) {
  Layer& l = layer();
  if (!serving()) return l.next.GetEyeGazesFB ? l.next.GetEyeGazesFB(tracker, info, gazes) : XR_ERROR_HANDLE_INVALID;
  if (!info || !gazes || info->type != XR_TYPE_EYE_GAZES_INFO_FB || gazes->type != XR_TYPE_EYE_GAZES_FB)
    return XR_ERROR_VALIDATION_FAILURE;
  if (info->time <= 0) return XR_ERROR_TIME_INVALID;
  const EyeTrackerSlot* slot = tracker_slot(tracker);
  if (!slot) return XR_ERROR_HANDLE_INVALID;
  const SessionSlot* session = find_session(slot->handle.load(std::memory_order_acquire));
  if (!session) return XR_ERROR_HANDLE_INVALID;
  for (auto& e : gazes->gaze) e = XrEyeGazeFB{XR_FALSE, identity_pose(), 0.0f};
  gazes->time = info->time;
  GazeNow g;
  // Invalid when the app has no focus, as the specification says, or without a sample.
  if (!session->focused.load(std::memory_order_acquire) || !l.feed || !l.feed->read(g)) return XR_SUCCESS;
  g = gaze_at(g, info->time);  // the newest sample, predicted to the asked time
  XrSpaceLocation head{};
  const XrResult r = locate_head(*session, info->baseSpace, info->time, head);
  if (XR_FAILED(r)) return r;
  if (!(head.locationFlags & XR_SPACE_LOCATION_ORIENTATION_VALID_BIT)) return XR_SUCCESS;
  for (int e = 0; e < 2; ++e) {
    if (!g.eye_tracked[e]) continue;
    const XrPosef eye_in_head{look_rotation(g.eye_dir[e]), {(e == 0 ? -0.5f : 0.5f) * g.ipd_m, 0, 0}};
    gazes->gaze[e] = XrEyeGazeFB{XR_TRUE, compose(head.pose, eye_in_head), g.confidence[e]};
  }
  // The time the gazes are for: info->time when predicted there, else the sample's own
  // (prediction off, an older foveald, or as far as the 50 ms horizon reaches).
  gazes->time = l.feed->to_xr_time(g.at_ns);
  return XR_SUCCESS;
}

namespace {
void fill_properties(XrBaseOutStructure* p) {
  if (serving()) reinterpret_cast<XrSystemEyeTrackingPropertiesFB*>(p)->supportsEyeTracking = XR_TRUE;
}
const Intercept kFunctions[] = {
    {"xrCreateEyeTrackerFB", FOVEAL_FN(layer_xrCreateEyeTrackerFB), true},
    {"xrDestroyEyeTrackerFB", FOVEAL_FN(layer_xrDestroyEyeTrackerFB), true},
    {"xrGetEyeGazesFB", FOVEAL_FN(layer_xrGetEyeGazesFB), true},
};
}  // namespace

const ServedExtension kFbEyeTrackingSocial = {
    XR_FB_EYE_TRACKING_SOCIAL_EXTENSION_NAME, 1, kFunctions, std::size(kFunctions),
    XR_TYPE_SYSTEM_EYE_TRACKING_PROPERTIES_FB, fill_properties, -1};

}  // namespace foveal::openxr

#include "gaze_reader.hpp"

#include <cstdio>
#include <cstring>

namespace example {

namespace {

bool ok(XrResult r, const char* what) {
  if (XR_SUCCEEDED(r)) return true;
  std::fprintf(stderr, "openxr_quad_views: %s failed (%d)\n", what, static_cast<int>(r));
  return false;
}

}  // namespace

std::unique_ptr<GazeReader> GazeReader::create(XrInstance instance, XrSession session) {
  std::unique_ptr<GazeReader> g(new GazeReader);
  g->session_ = session;
  XrActionSetCreateInfo si{XR_TYPE_ACTION_SET_CREATE_INFO};
  std::strcpy(si.actionSetName, "gaze");
  std::strcpy(si.localizedActionSetName, "Gaze");
  if (!ok(xrCreateActionSet(instance, &si, &g->set_), "xrCreateActionSet")) return nullptr;
  XrActionCreateInfo ai{XR_TYPE_ACTION_CREATE_INFO};
  ai.actionType = XR_ACTION_TYPE_POSE_INPUT;
  std::strcpy(ai.actionName, "gaze");
  std::strcpy(ai.localizedActionName, "Gaze");
  if (!ok(xrCreateAction(g->set_, &ai, &g->action_), "xrCreateAction")) return nullptr;
  XrPath profile = XR_NULL_PATH, pose = XR_NULL_PATH;
  if (!ok(xrStringToPath(instance, "/interaction_profiles/ext/eye_gaze_interaction", &profile), "xrStringToPath") ||
      !ok(xrStringToPath(instance, "/user/eyes_ext/input/gaze_ext/pose", &pose), "xrStringToPath"))
    return nullptr;
  const XrActionSuggestedBinding binding{g->action_, pose};
  XrInteractionProfileSuggestedBinding sb{XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING, nullptr, profile, 1, &binding};
  if (!ok(xrSuggestInteractionProfileBindings(instance, &sb), "xrSuggestInteractionProfileBindings")) return nullptr;
  XrSessionActionSetsAttachInfo at{XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO, nullptr, 1, &g->set_};
  if (!ok(xrAttachSessionActionSets(session, &at), "xrAttachSessionActionSets")) return nullptr;
  XrActionSpaceCreateInfo sp{XR_TYPE_ACTION_SPACE_CREATE_INFO, nullptr, g->action_, XR_NULL_PATH, {{0, 0, 0, 1}, {0, 0, 0}}};
  if (!ok(xrCreateActionSpace(session, &sp, &g->space_), "xrCreateActionSpace")) return nullptr;
  return g;
}

GazeReader::~GazeReader() {
  if (space_ != XR_NULL_HANDLE) xrDestroySpace(space_);
  if (set_ != XR_NULL_HANDLE) xrDestroyActionSet(set_);  // with its action
}

bool GazeReader::sync() {
  const XrActiveActionSet active{set_, XR_NULL_PATH};
  XrActionsSyncInfo si{XR_TYPE_ACTIONS_SYNC_INFO, nullptr, 1, &active};
  const XrResult r = xrSyncActions(session_, &si);
  return r == XR_SUCCESS || r == XR_SESSION_NOT_FOCUSED;
}

GazeReading GazeReader::read(XrSpace base, XrTime time) const {
  GazeReading out;
  XrActionStateGetInfo gi{XR_TYPE_ACTION_STATE_GET_INFO, nullptr, action_, XR_NULL_PATH};
  XrActionStatePose state{XR_TYPE_ACTION_STATE_POSE};
  if (XR_FAILED(xrGetActionStatePose(session_, &gi, &state))) return out;
  out.active = state.isActive;
  XrEyeGazeSampleTimeEXT sample{XR_TYPE_EYE_GAZE_SAMPLE_TIME_EXT};
  XrSpaceLocation loc{XR_TYPE_SPACE_LOCATION, &sample};
  if (!out.active || XR_FAILED(xrLocateSpace(space_, base, time, &loc))) return out;
  out.tracked = loc.locationFlags & XR_SPACE_LOCATION_ORIENTATION_VALID_BIT;
  out.sample_time = sample.time;
  out.orientation = loc.pose.orientation;
  return out;
}

}  // namespace example

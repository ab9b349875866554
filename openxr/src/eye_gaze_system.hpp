#pragma once
// XR_EXT_eye_gaze_interaction's calls (eye_gaze_interaction.cpp), for its row.
#include "layer.hpp"

namespace foveal::openxr {

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

}  // namespace foveal::openxr

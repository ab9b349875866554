/* XR_FB_eye_tracking_social (OpenXR 1.0.27, extension 203, revision 1): per-eye gaze.
 * Debian 12's OpenXR headers (1.0.20) predate it, so its few definitions are written
 * here from the OpenXR registry's specification. A newer openxr.h that defines the
 * extension wins: these are skipped. */
#ifndef FOVEAL_OPENXR_FB_EYE_TRACKING_SOCIAL_H
#define FOVEAL_OPENXR_FB_EYE_TRACKING_SOCIAL_H

#include <openxr/openxr.h>

#ifndef XR_FB_eye_tracking_social
#define XR_FB_eye_tracking_social 1
#define XR_FB_eye_tracking_social_SPEC_VERSION 1
#define XR_FB_EYE_TRACKING_SOCIAL_EXTENSION_NAME "XR_FB_eye_tracking_social"

XR_DEFINE_HANDLE(XrEyeTrackerFB)

#define XR_OBJECT_TYPE_EYE_TRACKER_FB ((XrObjectType)1000202000)
#define XR_TYPE_EYE_TRACKER_CREATE_INFO_FB ((XrStructureType)1000202001)
#define XR_TYPE_EYE_GAZES_INFO_FB ((XrStructureType)1000202002)
#define XR_TYPE_EYE_GAZES_FB ((XrStructureType)1000202003)
#define XR_TYPE_SYSTEM_EYE_TRACKING_PROPERTIES_FB ((XrStructureType)1000202004)

typedef enum XrEyePositionFB {
  XR_EYE_POSITION_LEFT_FB = 0,
  XR_EYE_POSITION_RIGHT_FB = 1,
  XR_EYE_POSITION_COUNT_FB = 2,
  XR_EYE_POSITION_MAX_ENUM_FB = 0x7FFFFFFF
} XrEyePositionFB;

typedef struct XrEyeGazeFB {
  XrBool32 isValid;
  XrPosef gazePose;
  float gazeConfidence;
} XrEyeGazeFB;

typedef struct XrEyeTrackerCreateInfoFB {
  XrStructureType type;
  const void *XR_MAY_ALIAS next;
} XrEyeTrackerCreateInfoFB;

typedef struct XrEyeGazesInfoFB {
  XrStructureType type;
  const void *XR_MAY_ALIAS next;
  XrSpace baseSpace;
  XrTime time;
} XrEyeGazesInfoFB;

typedef struct XrSystemEyeTrackingPropertiesFB {
  XrStructureType type;
  void *XR_MAY_ALIAS next;
  XrBool32 supportsEyeTracking;
} XrSystemEyeTrackingPropertiesFB;

typedef struct XrEyeGazesFB {
  XrStructureType type;
  void *XR_MAY_ALIAS next;
  XrEyeGazeFB gaze[XR_EYE_POSITION_COUNT_FB];
  XrTime time;
} XrEyeGazesFB;

typedef XrResult(XRAPI_PTR *PFN_xrCreateEyeTrackerFB)(XrSession session, const XrEyeTrackerCreateInfoFB *createInfo,
                                                      XrEyeTrackerFB *eyeTracker);
typedef XrResult(XRAPI_PTR *PFN_xrDestroyEyeTrackerFB)(XrEyeTrackerFB eyeTracker);
typedef XrResult(XRAPI_PTR *PFN_xrGetEyeGazesFB)(XrEyeTrackerFB eyeTracker, const XrEyeGazesInfoFB *gazeInfo,
                                                 XrEyeGazesFB *eyeGazes);
#endif

#endif

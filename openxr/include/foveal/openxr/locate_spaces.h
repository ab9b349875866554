/* xrLocateSpaces: OpenXR 1.1 core (and XR_KHR_locate_spaces, extension 472, revision 1,
 * its 1.0 form), and the 1.1 name of the inset view configuration. Debian 12's OpenXR
 * headers (1.0.20) predate both, so these few definitions are written here from the
 * OpenXR registry's specification. A newer openxr.h that defines them wins: each block
 * steps aside where its guard (XR_VERSION_1_1, XR_KHR_locate_spaces) is defined. */
#ifndef FOVEAL_OPENXR_LOCATE_SPACES_H
#define FOVEAL_OPENXR_LOCATE_SPACES_H

#include <openxr/openxr.h>

#ifndef XR_VERSION_1_1
#define XR_TYPE_SPACES_LOCATE_INFO ((XrStructureType)1000471000)
#define XR_TYPE_SPACE_LOCATIONS ((XrStructureType)1000471001)
#define XR_TYPE_SPACE_VELOCITIES ((XrStructureType)1000471002)
/* The value of XR_VIEW_CONFIGURATION_TYPE_PRIMARY_QUAD_VARJO (XR_VARJO_quad_views). */
#define XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO_WITH_FOVEATED_INSET ((XrViewConfigurationType)1000037000)

typedef struct XrSpacesLocateInfo {
  XrStructureType type;
  const void *XR_MAY_ALIAS next;
  XrSpace baseSpace;
  XrTime time;
  uint32_t spaceCount;
  const XrSpace *spaces;
} XrSpacesLocateInfo;

typedef struct XrSpaceLocationData {
  XrSpaceLocationFlags locationFlags;
  XrPosef pose;
} XrSpaceLocationData;

typedef struct XrSpaceLocations {
  XrStructureType type;
  void *XR_MAY_ALIAS next;
  uint32_t locationCount;
  XrSpaceLocationData *locations;
} XrSpaceLocations;

typedef struct XrSpaceVelocityData {
  XrSpaceVelocityFlags velocityFlags;
  XrVector3f linearVelocity;
  XrVector3f angularVelocity;
} XrSpaceVelocityData;

/* Extends XrSpaceLocations. */
typedef struct XrSpaceVelocities {
  XrStructureType type;
  void *XR_MAY_ALIAS next;
  uint32_t velocityCount;
  XrSpaceVelocityData *velocities;
} XrSpaceVelocities;

typedef XrResult(XRAPI_PTR *PFN_xrLocateSpaces)(XrSession session, const XrSpacesLocateInfo *locateInfo,
                                                XrSpaceLocations *spaceLocations);
#endif

#ifndef XR_KHR_locate_spaces
#define XR_KHR_locate_spaces 1
#define XR_KHR_locate_spaces_SPEC_VERSION 1
#define XR_KHR_LOCATE_SPACES_EXTENSION_NAME "XR_KHR_locate_spaces"
#define XR_TYPE_SPACES_LOCATE_INFO_KHR XR_TYPE_SPACES_LOCATE_INFO
#define XR_TYPE_SPACE_LOCATIONS_KHR XR_TYPE_SPACE_LOCATIONS
#define XR_TYPE_SPACE_VELOCITIES_KHR XR_TYPE_SPACE_VELOCITIES
typedef XrSpacesLocateInfo XrSpacesLocateInfoKHR;
typedef XrSpaceLocationData XrSpaceLocationDataKHR;
typedef XrSpaceLocations XrSpaceLocationsKHR;
typedef XrSpaceVelocityData XrSpaceVelocityDataKHR;
typedef XrSpaceVelocities XrSpaceVelocitiesKHR;
typedef XrResult(XRAPI_PTR *PFN_xrLocateSpacesKHR)(XrSession session, const XrSpacesLocateInfoKHR *locateInfo,
                                                   XrSpaceLocationsKHR *spaceLocations);
#endif

#endif

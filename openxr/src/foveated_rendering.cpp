// XR_VARJO_foveated_rendering on top of the layer's quad views: the system property that
// says gaze-driven rendering is available, the foveated sizes and fields (quad_views.cpp
// reads XrFoveatedViewConfigurationViewVARJO and XrViewLocateFoveatedRenderingVARJO),
// and the COMBINED_EYE_VARJO reference space: the head turned along foveald's combined
// gaze, its orientation tracked only while that gaze is. docs/openxr.md.
#include <iterator>

#include "layer.hpp"
#include "pose_math.hpp"

namespace foveal::openxr {

namespace {

bool serving() { return layer().foveated_rendering(); }

bool gaze_now(GazeNow& g) {
  const Layer& l = layer();
  return l.feed && l.feed->read(g) && g.tracked;
}

void fill_properties(XrBaseOutStructure* p) {
  GazeNow g;
  if (serving())
    reinterpret_cast<XrSystemFoveatedRenderingPropertiesVARJO*>(p)->supportsFoveatedRendering = gaze_now(g) ? XR_TRUE : XR_FALSE;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrCreateReferenceSpace(XrSession session, const XrReferenceSpaceCreateInfo* info,
                                                            XrSpace* space) {
  Layer& l = layer();
  if (!serving() || !info || !space || info->referenceSpaceType != XR_REFERENCE_SPACE_TYPE_COMBINED_EYE_VARJO)
    return l.next.CreateReferenceSpace(session, info, space);
  if (!find_session(session)) return XR_ERROR_HANDLE_INVALID;
  // A VIEW space of the runtime stands for it; the gaze turn is added at each locate.
  XrReferenceSpaceCreateInfo down{XR_TYPE_REFERENCE_SPACE_CREATE_INFO, nullptr, XR_REFERENCE_SPACE_TYPE_VIEW,
                                  identity_pose()};
  const XrResult r = l.next.CreateReferenceSpace(session, &down, space);
  if (XR_FAILED(r)) return r;
  std::lock_guard lock(l.mutex);
  const bool claimed = claim_slot(l.spaces, *space, [&](SpaceSlot& s) {
    s.action = -1;
    s.session = session;
    s.pose_in_action = info->poseInReferenceSpace;
  });
  if (!claimed) {
    l.next.DestroySpace(*space);
    *space = XR_NULL_HANDLE;
    return XR_ERROR_LIMIT_REACHED;
  }
  return r;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrEnumerateReferenceSpaces(XrSession session, std::uint32_t capacity,
                                                                std::uint32_t* count, XrReferenceSpaceType* spaces) {
  Layer& l = layer();
  if (!serving() || !count) return l.next.EnumerateReferenceSpaces(session, capacity, count, spaces);
  XrReferenceSpaceType own[16];
  std::uint32_t n = 0;
  const XrResult r = l.next.EnumerateReferenceSpaces(session, 15, &n, own);
  if (XR_FAILED(r)) return r;
  own[n++] = XR_REFERENCE_SPACE_TYPE_COMBINED_EYE_VARJO;
  *count = n;
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < n || !spaces) return XR_ERROR_SIZE_INSUFFICIENT;
  for (std::uint32_t i = 0; i < n; ++i) spaces[i] = own[i];
  return XR_SUCCESS;
}

const Intercept kFunctions[] = {
    {"xrCreateReferenceSpace", FOVEAL_FN(layer_xrCreateReferenceSpace), false},
    {"xrEnumerateReferenceSpaces", FOVEAL_FN(layer_xrEnumerateReferenceSpaces), false},
};

}  // namespace

XrResult locate_combined_eye_space(XrSpace space, XrSpace base, XrTime time, XrSpaceLocation* location,
                                   const SpaceSlot* sp, const SpaceSlot* bp) {
  Layer& l = layer();
  const bool space_eye = sp && sp->action < 0, base_eye = bp && bp->action < 0;
  // The runtime locates the VIEW spaces standing for them; the gaze turns are applied here.
  const XrResult r = l.next.LocateSpace(space, base, time, location);
  if (XR_FAILED(r) || !(location->locationFlags & XR_SPACE_LOCATION_ORIENTATION_VALID_BIT)) return r;
  GazeNow g;
  const bool tracked = gaze_now(g);
  if (tracked) g = gaze_at(g, time);  // predicted to the locate's time
  const XrPosef turn{tracked ? look_rotation(g.combined) : XrQuaternionf{0, 0, 0, 1}, {0, 0, 0}};
  XrPosef pose = location->pose;
  if (space_eye) pose = compose(pose, compose(turn, sp->pose_in_action));
  if (base_eye) pose = compose(inverse(compose(turn, bp->pose_in_action)), pose);
  location->pose = pose;
  if (!tracked) location->locationFlags &= ~static_cast<XrSpaceLocationFlags>(XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT);
  // Velocities of a turned space are not the runtime's: none reported.
  for (auto* p = reinterpret_cast<XrBaseOutStructure*>(location->next); p; p = p->next)
    if (p->type == XR_TYPE_SPACE_VELOCITY) reinterpret_cast<XrSpaceVelocity*>(p)->velocityFlags = 0;
  return r;
}

const ServedExtension kVarjoFoveatedRendering = {
    XR_VARJO_FOVEATED_RENDERING_EXTENSION_NAME, 2, kFunctions, std::size(kFunctions),
    XR_TYPE_SYSTEM_FOVEATED_RENDERING_PROPERTIES_VARJO, fill_properties,
    static_cast<int>(Ext::varjo_quad_views)};

}  // namespace foveal::openxr

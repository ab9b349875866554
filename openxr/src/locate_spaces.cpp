// xrLocateSpaces (OpenXR 1.1 core) and xrLocateSpacesKHR (XR_KHR_locate_spaces, the same
// call for a 1.0 instance): many spaces located in one base at one time. The runtime
// cannot locate the layer's spaces (an eye-gaze action space is bound to nothing it
// knows; a COMBINED_EYE_VARJO space is a plain VIEW space to it), so each of those is
// answered as xrLocateSpace answers it (the same latched gaze, predicted to the same
// time, the same flags), and the rest go down in one call. Not a served extension: the
// layer adds neither function to an instance, it answers them for its own spaces where
// the runtime has them. docs/openxr.md, "Locating many spaces at once".
#include "locate_spaces.hpp"

#include <cstdint>
#include <cstring>

#include "served_extension.hpp"

namespace foveal::openxr {

namespace {

// The next layer's functions for the current instance (set at its creation).
PFN_xrLocateSpaces g_core = nullptr;
PFN_xrLocateSpacesKHR g_khr = nullptr;

XrSpaceVelocities* velocities_of(const XrSpaceLocations* out) {
  for (auto* p = static_cast<XrBaseOutStructure*>(out->next); p; p = p->next)
    if (p->type == XR_TYPE_SPACE_VELOCITIES) return reinterpret_cast<XrSpaceVelocities*>(p);
  return nullptr;
}

XrResult locate_spaces(PFN_xrLocateSpaces next, XrSession session, const XrSpacesLocateInfo* info,
                       XrSpaceLocations* out) {
  // Anything malformed goes down untouched: the runtime's validation answers it.
  if (!info || !out || info->type != XR_TYPE_SPACES_LOCATE_INFO || out->type != XR_TYPE_SPACE_LOCATIONS ||
      info->spaceCount == 0 || info->spaceCount != out->locationCount || !info->spaces || !out->locations)
    return next(session, info, out);
  XrSpaceVelocities* vel = velocities_of(out);
  if (vel && (vel->velocityCount != info->spaceCount || !vel->velocities)) return next(session, info, out);
  const bool base_ours = layer_locates(info->baseSpace);
  bool any = base_ours;
  for (std::uint32_t i = 0; i < info->spaceCount && !any; ++i) any = layer_locates(info->spaces[i]);
  if (!any) return next(session, info, out);  // the common case: no copy, no second look
  if (!base_ours) {
    // Every space in one call (the runtime knows each handle: the layer's own come back
    // untracked, or as the VIEW space behind them), then the layer's entries are replaced.
    const XrResult r = next(session, info, out);
    if (XR_FAILED(r)) return r;
  } else if (info->time <= 0) {
    return XR_ERROR_TIME_INVALID;  // what the runtime says to such a time
  }
  // Relative to a base of the layer's, every entry is the layer's to answer.
  for (std::uint32_t i = 0; i < info->spaceCount; ++i) {
    if (!base_ours && !layer_locates(info->spaces[i])) continue;
    XrSpaceVelocity v{XR_TYPE_SPACE_VELOCITY, nullptr, 0, {0, 0, 0}, {0, 0, 0}};
    XrSpaceLocation one{XR_TYPE_SPACE_LOCATION, vel ? &v : nullptr, 0, {{0, 0, 0, 1}, {0, 0, 0}}};
    const XrResult r = locate_space(info->spaces[i], info->baseSpace, info->time, &one);
    if (XR_FAILED(r)) return r;
    out->locations[i] = {one.locationFlags, one.pose};
    if (vel) vel->velocities[i] = {v.velocityFlags, v.linearVelocity, v.angularVelocity};
  }
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrLocateSpaces(XrSession session, const XrSpacesLocateInfo* info,
                                                    XrSpaceLocations* out) {
  return locate_spaces(g_core, session, info, out);
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrLocateSpacesKHR(XrSession session, const XrSpacesLocateInfoKHR* info,
                                                       XrSpaceLocationsKHR* out) {
  return locate_spaces(g_khr, session, info, out);
}

}  // namespace

void load_locate_spaces(XrInstance instance, PFN_xrGetInstanceProcAddr next, bool core, bool khr) {
  g_core = nullptr;
  g_khr = nullptr;
  PFN_xrVoidFunction f = nullptr;
  if (core && XR_SUCCEEDED(next(instance, "xrLocateSpaces", &f)) && f) g_core = reinterpret_cast<PFN_xrLocateSpaces>(f);
  f = nullptr;
  if (khr && XR_SUCCEEDED(next(instance, "xrLocateSpacesKHR", &f)) && f)
    g_khr = reinterpret_cast<PFN_xrLocateSpacesKHR>(f);
}

PFN_xrVoidFunction locate_spaces_function(const char* name) {
  if (g_core && std::strcmp(name, "xrLocateSpaces") == 0) return FOVEAL_FN(layer_xrLocateSpaces);
  if (g_khr && std::strcmp(name, "xrLocateSpacesKHR") == 0) return FOVEAL_FN(layer_xrLocateSpacesKHR);
  return nullptr;
}

}  // namespace foveal::openxr

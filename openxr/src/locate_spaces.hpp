#pragma once
// xrLocateSpaces (OpenXR 1.1 core) and xrLocateSpacesKHR (XR_KHR_locate_spaces): the
// layer's spaces among many answered as xrLocateSpace answers them (locate_spaces.cpp).
#include <openxr/openxr.h>

#include "foveal/openxr/locate_spaces.h"

namespace foveal::openxr {

/// Loads the next layer's entry points for a new instance: xrLocateSpaces where the
/// runtime accepted apiVersion 1.1 (`core`), xrLocateSpacesKHR where the app enabled
/// XR_KHR_locate_spaces (`khr`). Either is null where the chain below does not give it.
void load_locate_spaces(XrInstance instance, PFN_xrGetInstanceProcAddr next, bool core, bool khr);

/// The layer's function for `name` (xrLocateSpaces, xrLocateSpacesKHR) where it was
/// loaded for this instance; null otherwise (the chain below answers the name).
PFN_xrVoidFunction locate_spaces_function(const char* name);

/// xrLocateSpace as the layer answers it (layer.cpp): eye-gaze action spaces and
/// COMBINED_EYE_VARJO spaces from foveald's gaze, every other pair by the runtime.
XrResult locate_space(XrSpace space, XrSpace base, XrTime time, XrSpaceLocation* location);

/// The layer, not the runtime, answers locates that involve `space`.
bool layer_locates(XrSpace space);

}  // namespace foveal::openxr

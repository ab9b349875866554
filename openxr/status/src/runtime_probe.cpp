// Asks the runtime the loader picks whether its HMD system has eye gaze, with foveal's
// layer turned off for this process so that the answer is the runtime's own. Runs in the
// probe's child process only (probe_process.cpp).
#include <cstdlib>
#include <cstring>

#include <openxr/openxr.h>

#include "probe.hpp"

namespace foveal::openxr {

RuntimeGaze probe_runtime_here() {
  RuntimeGaze g;
  ::setenv("FOVEAL_OPENXR_DISABLE", "1", 1);  // the loader reads it at xrCreateInstance
  std::uint32_t n = 0;
  XrResult r = xrEnumerateInstanceExtensionProperties(nullptr, 0, &n, nullptr);
  if (XR_FAILED(r)) {
    g.message = "the loader could not load a runtime (error " + std::to_string(r) + ")";
    g.runtime_failed = true;
    return g;
  }
  std::vector<XrExtensionProperties> props(n, {XR_TYPE_EXTENSION_PROPERTIES, nullptr, {}, 0});
  xrEnumerateInstanceExtensionProperties(nullptr, n, &n, props.data());
  bool headless = false;
  for (const auto& p : props) {
    g.lists_eye_gaze_interaction |= std::strcmp(p.extensionName, XR_EXT_EYE_GAZE_INTERACTION_EXTENSION_NAME) == 0;
    headless |= std::strcmp(p.extensionName, XR_MND_HEADLESS_EXTENSION_NAME) == 0;
  }
  std::vector<const char*> wanted;
  if (g.lists_eye_gaze_interaction) wanted.push_back(XR_EXT_EYE_GAZE_INTERACTION_EXTENSION_NAME);
  if (headless) wanted.push_back(XR_MND_HEADLESS_EXTENSION_NAME);
  XrInstanceCreateInfo ci{XR_TYPE_INSTANCE_CREATE_INFO, nullptr, 0, {}, 0, nullptr,
                          static_cast<std::uint32_t>(wanted.size()), wanted.data()};
  std::strncpy(ci.applicationInfo.applicationName, "foveal openxr", XR_MAX_APPLICATION_NAME_SIZE - 1);
  ci.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
  XrInstance instance = XR_NULL_HANDLE;
  if (XR_FAILED(r = xrCreateInstance(&ci, &instance))) {
    g.message = "the runtime refused an instance (error " + std::to_string(r) + ")";
    g.runtime_failed = true;
    return g;
  }
  XrInstanceProperties ip{XR_TYPE_INSTANCE_PROPERTIES, nullptr, 0, {}};
  if (XR_SUCCEEDED(xrGetInstanceProperties(instance, &ip))) g.runtime_name = ip.runtimeName;
  XrSystemGetInfo sgi{XR_TYPE_SYSTEM_GET_INFO, nullptr, XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY};
  XrSystemId system = XR_NULL_SYSTEM_ID;
  if (XR_FAILED(r = xrGetSystem(instance, &sgi, &system))) {
    g.message = "no head-mounted display system now (error " + std::to_string(r) + ")";
  } else {
    XrSystemEyeGazeInteractionPropertiesEXT eg{XR_TYPE_SYSTEM_EYE_GAZE_INTERACTION_PROPERTIES_EXT, nullptr, XR_FALSE};
    XrSystemProperties sp{XR_TYPE_SYSTEM_PROPERTIES, g.lists_eye_gaze_interaction ? &eg : nullptr, 0, 0, {}, {}, {}};
    if (XR_SUCCEEDED(xrGetSystemProperties(instance, system, &sp))) {
      g.probed = true;
      g.system_name = sp.systemName;
      g.supports_eye_gaze_interaction = eg.supportsEyeGazeInteraction == XR_TRUE;
    }
  }
  xrDestroyInstance(instance);
  return g;
}

}  // namespace foveal::openxr

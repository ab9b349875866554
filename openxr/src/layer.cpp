// The layer's entry points: negotiation with the loader, instance creation (which
// extensions go down to the runtime), xrGetInstanceProcAddr, system properties, and
// the session bookkeeping gaze needs (focus, a VIEW space). docs/openxr.md.
#include "layer.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "loader_interface.h"

namespace foveal::openxr {

Layer& layer() {
  static Layer l;
  return l;
}

void log_line(const char* text) { std::fprintf(stderr, "foveal-openxr: %s\n", text); }

namespace {

GazeMode mode_from_environment() {
  const char* v = std::getenv("FOVEAL_OPENXR_GAZE");
  if (!v || !*v || std::string_view(v) == "auto") return GazeMode::automatic;
  if (std::string_view(v) == "foveal") return GazeMode::foveal;
  if (std::string_view(v) == "runtime") return GazeMode::runtime;
  log_line("FOVEAL_OPENXR_GAZE must be auto, foveal or runtime; using auto");
  return GazeMode::automatic;
}

template <typename F>
void load(XrInstance instance, const char* name, F& fn) {
  PFN_xrVoidFunction f = nullptr;
  if (XR_SUCCEEDED(layer().next.GetInstanceProcAddr(instance, name, &f))) fn = reinterpret_cast<F>(f);
}

/// The runtime's instance extensions, asked through the chain below the layer.
std::vector<std::string> runtime_extensions(PFN_xrGetInstanceProcAddr gipa) {
  std::vector<std::string> names;
  PFN_xrVoidFunction f = nullptr;
  if (XR_FAILED(gipa(XR_NULL_HANDLE, "xrEnumerateInstanceExtensionProperties", &f)) || !f) return names;
  auto enumerate = reinterpret_cast<PFN_xrEnumerateInstanceExtensionProperties>(f);
  std::uint32_t n = 0;
  if (XR_FAILED(enumerate(nullptr, 0, &n, nullptr))) return names;
  std::vector<XrExtensionProperties> props(n, {XR_TYPE_EXTENSION_PROPERTIES, nullptr, {}, 0});
  if (XR_FAILED(enumerate(nullptr, n, &n, props.data()))) return names;
  for (std::uint32_t i = 0; i < n; ++i) names.emplace_back(props[i].extensionName);
  return names;
}

bool has(const std::vector<std::string>& names, const char* name) {
  for (const auto& n : names)
    if (n == name) return true;
  return false;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrGetInstanceProcAddr(XrInstance instance, const char* name,
                                                           PFN_xrVoidFunction* function);

XRAPI_ATTR XrResult XRAPI_CALL layer_xrCreateApiLayerInstance(const XrInstanceCreateInfo* info,
                                                              const XrApiLayerCreateInfo* api_layer_info,
                                                              XrInstance* instance) {
  if (!info || !api_layer_info || !instance || !api_layer_info->nextInfo) return XR_ERROR_VALIDATION_FAILURE;
  Layer& l = layer();
  std::lock_guard lock(l.mutex);
  if (l.instance != XR_NULL_HANDLE) {
    log_line("a second XrInstance in one process: the layer serves one at a time");
    return XR_ERROR_LIMIT_REACHED;
  }
  const XrApiLayerNextInfo* next_info = api_layer_info->nextInfo;
  if (next_info->structType != XR_LOADER_INTERFACE_STRUCT_API_LAYER_NEXT_INFO ||
      std::strcmp(next_info->layerName, kLayerName) != 0)
    return XR_ERROR_INITIALIZATION_FAILED;
  l.mode = mode_from_environment();

  // The runtime sees the extensions the layer provides only where it has them itself,
  // and gets XR_KHR_convert_timespec_time for the gaze samples' times.
  // Asked of the end of the chain (the runtime): layers below answer only for instances.
  const XrApiLayerNextInfo* last = next_info;
  while (last->next) last = last->next;
  const std::vector<std::string> below = runtime_extensions(last->nextGetInstanceProcAddr);
  std::vector<const char*> enabled;
  l.app_ext = l.app_fb = false;
  bool want_convert = has(below, XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME);
  for (std::uint32_t i = 0; i < info->enabledExtensionCount; ++i) {
    const char* e = info->enabledExtensionNames[i];
    const bool is_ext = std::strcmp(e, XR_EXT_EYE_GAZE_INTERACTION_EXTENSION_NAME) == 0;
    const bool is_fb = std::strcmp(e, XR_FB_EYE_TRACKING_SOCIAL_EXTENSION_NAME) == 0;
    l.app_ext |= is_ext;
    l.app_fb |= is_fb;
    if (std::strcmp(e, XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME) == 0) want_convert = false;  // already there
    if ((is_ext || is_fb) && l.mode != GazeMode::runtime && !has(below, e)) continue;
    enabled.push_back(e);
  }
  if (want_convert) enabled.push_back(XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME);
  l.runtime_ext = l.app_ext && has(below, XR_EXT_EYE_GAZE_INTERACTION_EXTENSION_NAME);
  l.runtime_fb = l.app_fb && has(below, XR_FB_EYE_TRACKING_SOCIAL_EXTENSION_NAME);

  XrInstanceCreateInfo down = *info;
  down.enabledExtensionCount = static_cast<std::uint32_t>(enabled.size());
  down.enabledExtensionNames = enabled.data();
  XrApiLayerCreateInfo down_layer = *api_layer_info;
  down_layer.nextInfo = next_info->next;
  const XrResult r = next_info->nextCreateApiLayerInstance(&down, &down_layer, instance);
  if (XR_FAILED(r)) return r;

  l.instance = *instance;
  l.next = Next{};
  l.next.GetInstanceProcAddr = next_info->nextGetInstanceProcAddr;
  Next& n = l.next;
  load(*instance, "xrDestroyInstance", n.DestroyInstance);
  load(*instance, "xrGetSystemProperties", n.GetSystemProperties);
  load(*instance, "xrCreateSession", n.CreateSession);
  load(*instance, "xrDestroySession", n.DestroySession);
  load(*instance, "xrPollEvent", n.PollEvent);
  load(*instance, "xrCreateReferenceSpace", n.CreateReferenceSpace);
  load(*instance, "xrCreateActionSpace", n.CreateActionSpace);
  load(*instance, "xrDestroySpace", n.DestroySpace);
  load(*instance, "xrLocateSpace", n.LocateSpace);
  load(*instance, "xrCreateActionSet", n.CreateActionSet);
  load(*instance, "xrDestroyActionSet", n.DestroyActionSet);
  load(*instance, "xrCreateAction", n.CreateAction);
  load(*instance, "xrDestroyAction", n.DestroyAction);
  load(*instance, "xrSuggestInteractionProfileBindings", n.SuggestInteractionProfileBindings);
  load(*instance, "xrAttachSessionActionSets", n.AttachSessionActionSets);
  load(*instance, "xrGetCurrentInteractionProfile", n.GetCurrentInteractionProfile);
  load(*instance, "xrSyncActions", n.SyncActions);
  load(*instance, "xrGetActionStatePose", n.GetActionStatePose);
  load(*instance, "xrStringToPath", n.StringToPath);
  if (want_convert || has(below, XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME))
    load(*instance, "xrConvertTimespecTimeToTimeKHR", n.ConvertTimespecTimeToTimeKHR);
  if (l.runtime_fb) {
    load(*instance, "xrCreateEyeTrackerFB", n.CreateEyeTrackerFB);
    load(*instance, "xrDestroyEyeTrackerFB", n.DestroyEyeTrackerFB);
    load(*instance, "xrGetEyeGazesFB", n.GetEyeGazesFB);
  }
  n.StringToPath(*instance, "/interaction_profiles/ext/eye_gaze_interaction", &l.profile_path);
  n.StringToPath(*instance, "/user/eyes_ext", &l.eyes_path);
  n.StringToPath(*instance, "/user/eyes_ext/input/gaze_ext/pose", &l.gaze_pose_path);
  n.StringToPath(*instance, "/user/eyes_ext/input/gaze_ext", &l.gaze_path);
  l.decided = l.attached = false;
  l.serve_ext = l.serve_fb = false;
  if (l.mode != GazeMode::runtime && (l.app_ext || l.app_fb)) {
    const XrInstance inst = *instance;
    auto convert = n.ConvertTimespecTimeToTimeKHR;
    l.feed = std::make_unique<GazeFeed>(
        [inst, convert](std::int64_t t_ns, XrTime& out) {
          if (!convert) return false;
          const timespec ts{static_cast<time_t>(t_ns / 1'000'000'000), static_cast<long>(t_ns % 1'000'000'000)};
          return XR_SUCCEEDED(convert(inst, &ts, &out));
        },
        log_line);
  }
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrDestroyInstance(XrInstance instance) {
  Layer& l = layer();
  PFN_xrDestroyInstance destroy = l.next.DestroyInstance;
  {
    std::lock_guard lock(l.mutex);
    l.feed.reset();  // its thread converts times through the instance: stop it first
    for (auto& a : l.actions) a.handle.store(XR_NULL_HANDLE), a.gaze = false, a.set_active = false;
    for (auto& s : l.spaces) s.handle.store(XR_NULL_HANDLE);
    for (auto& s : l.sessions) s.handle.store(XR_NULL_HANDLE);
    for (auto& t : l.trackers) t.handle.store(XR_NULL_HANDLE);
    l.instance = XR_NULL_HANDLE;
  }
  return destroy ? destroy(instance) : XR_ERROR_HANDLE_INVALID;
}

/// Takes the structs of `type` out of an output chain (the runtime does not know them);
/// returns the one taken, to be put back with restore().
XrBaseOutStructure* unlink(void* chain_head, XrStructureType type) {
  auto* prev = static_cast<XrBaseOutStructure*>(chain_head);
  while (prev && prev->next) {
    if (prev->next->type == type) {
      XrBaseOutStructure* taken = prev->next;
      prev->next = taken->next;
      taken->next = reinterpret_cast<XrBaseOutStructure*>(prev);  // remembers where it was
      return taken;
    }
    prev = prev->next;
  }
  return nullptr;
}

void restore(XrBaseOutStructure* taken) {
  if (!taken) return;
  auto* prev = reinterpret_cast<XrBaseOutStructure*>(taken->next);
  taken->next = prev->next;
  prev->next = taken;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrGetSystemProperties(XrInstance instance, XrSystemId system,
                                                           XrSystemProperties* props) {
  Layer& l = layer();
  if (l.mode == GazeMode::runtime || !props) return l.next.GetSystemProperties(instance, system, props);
  decide_serving(system);
  XrBaseOutStructure* ext = l.runtime_ext ? nullptr : unlink(props, XR_TYPE_SYSTEM_EYE_GAZE_INTERACTION_PROPERTIES_EXT);
  XrBaseOutStructure* fb = l.runtime_fb ? nullptr : unlink(props, XR_TYPE_SYSTEM_EYE_TRACKING_PROPERTIES_FB);
  const XrResult r = l.next.GetSystemProperties(instance, system, props);
  restore(fb);
  restore(ext);
  if (XR_FAILED(r)) return r;
  for (auto* p = reinterpret_cast<XrBaseOutStructure*>(props->next); p; p = p->next) {
    if (p->type == XR_TYPE_SYSTEM_EYE_GAZE_INTERACTION_PROPERTIES_EXT && l.app_ext && l.serve_ext)
      reinterpret_cast<XrSystemEyeGazeInteractionPropertiesEXT*>(p)->supportsEyeGazeInteraction = XR_TRUE;
    if (p->type == XR_TYPE_SYSTEM_EYE_TRACKING_PROPERTIES_FB && l.app_fb && l.serve_fb)
      reinterpret_cast<XrSystemEyeTrackingPropertiesFB*>(p)->supportsEyeTracking = XR_TRUE;
  }
  return r;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrCreateSession(XrInstance instance, const XrSessionCreateInfo* info,
                                                     XrSession* session) {
  Layer& l = layer();
  const XrResult r = l.next.CreateSession(instance, info, session);
  if (XR_FAILED(r) || l.mode == GazeMode::runtime || !(l.app_ext || l.app_fb)) return r;
  decide_serving(info->systemId);
  std::lock_guard lock(l.mutex);
  XrReferenceSpaceCreateInfo view_info{XR_TYPE_REFERENCE_SPACE_CREATE_INFO, nullptr, XR_REFERENCE_SPACE_TYPE_VIEW,
                                       {{0, 0, 0, 1}, {0, 0, 0}}};
  XrSpace view = XR_NULL_HANDLE;
  if (XR_FAILED(l.next.CreateReferenceSpace(*session, &view_info, &view))) {
    log_line("the runtime refused a VIEW space: no eye gaze in this session");
    return r;
  }
  const bool claimed = claim_slot(l.sessions, *session, [view](SessionSlot& slot) {
    slot.view = view;
    slot.focused = false;
    slot.gaze_active = false;
  });
  if (!claimed) {
    l.next.DestroySpace(view);
    log_line("more than 4 sessions at once: no eye gaze in this one");
  }
  return r;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrDestroySession(XrSession session) {
  Layer& l = layer();
  {
    std::lock_guard lock(l.mutex);
    if (SessionSlot* s = find_session(session)) {
      s->handle.store(XR_NULL_HANDLE);
      l.next.DestroySpace(s->view);
    }
    for (auto& t : l.trackers)
      if (t.handle.load() == session) t.handle.store(XR_NULL_HANDLE);
    for (auto& sp : l.spaces)
      if (sp.handle.load() != XR_NULL_HANDLE && sp.session == session) sp.handle.store(XR_NULL_HANDLE);
  }
  return l.next.DestroySession(session);
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrPollEvent(XrInstance instance, XrEventDataBuffer* event) {
  const XrResult r = layer().next.PollEvent(instance, event);
  // Action state is active only while the session has focus (the specification's rule).
  if (r == XR_SUCCESS && event->type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) {
    const auto* e = reinterpret_cast<const XrEventDataSessionStateChanged*>(event);
    if (SessionSlot* s = find_session(e->session)) s->focused.store(e->state == XR_SESSION_STATE_FOCUSED);
  }
  return r;
}

struct Intercept {
  const char* name;
  PFN_xrVoidFunction fn;
  int needs;  ///< 0 always, 1 the app enabled XR_EXT_eye_gaze_interaction or the FB one, 2 the FB one
};

#define FOVEAL_FN(f) reinterpret_cast<PFN_xrVoidFunction>(f)
const Intercept kIntercepts[] = {
    {"xrGetInstanceProcAddr", FOVEAL_FN(layer_xrGetInstanceProcAddr), 0},
    {"xrDestroyInstance", FOVEAL_FN(layer_xrDestroyInstance), 0},
    {"xrGetSystemProperties", FOVEAL_FN(layer_xrGetSystemProperties), 1},
    {"xrCreateSession", FOVEAL_FN(layer_xrCreateSession), 1},
    {"xrDestroySession", FOVEAL_FN(layer_xrDestroySession), 1},
    {"xrPollEvent", FOVEAL_FN(layer_xrPollEvent), 1},
    {"xrCreateAction", FOVEAL_FN(layer_xrCreateAction), 1},
    {"xrDestroyAction", FOVEAL_FN(layer_xrDestroyAction), 1},
    {"xrDestroyActionSet", FOVEAL_FN(layer_xrDestroyActionSet), 1},
    {"xrSuggestInteractionProfileBindings", FOVEAL_FN(layer_xrSuggestInteractionProfileBindings), 1},
    {"xrAttachSessionActionSets", FOVEAL_FN(layer_xrAttachSessionActionSets), 1},
    {"xrGetCurrentInteractionProfile", FOVEAL_FN(layer_xrGetCurrentInteractionProfile), 1},
    {"xrSyncActions", FOVEAL_FN(layer_xrSyncActions), 1},
    {"xrGetActionStatePose", FOVEAL_FN(layer_xrGetActionStatePose), 1},
    {"xrCreateActionSpace", FOVEAL_FN(layer_xrCreateActionSpace), 1},
    {"xrDestroySpace", FOVEAL_FN(layer_xrDestroySpace), 1},
    {"xrLocateSpace", FOVEAL_FN(layer_xrLocateSpace), 1},
    {"xrCreateEyeTrackerFB", FOVEAL_FN(layer_xrCreateEyeTrackerFB), 2},
    {"xrDestroyEyeTrackerFB", FOVEAL_FN(layer_xrDestroyEyeTrackerFB), 2},
    {"xrGetEyeGazesFB", FOVEAL_FN(layer_xrGetEyeGazesFB), 2},
};
#undef FOVEAL_FN

XRAPI_ATTR XrResult XRAPI_CALL layer_xrGetInstanceProcAddr(XrInstance instance, const char* name,
                                                           PFN_xrVoidFunction* function) {
  Layer& l = layer();
  if (!name || !function) return XR_ERROR_VALIDATION_FAILURE;
  // In pass-through mode, or for an app that asked for no gaze, the layer is not there.
  const bool active = l.mode != GazeMode::runtime && instance != XR_NULL_HANDLE && instance == l.instance;
  for (const Intercept& i : kIntercepts) {
    if (std::strcmp(name, i.name) != 0) continue;
    const bool wanted = i.needs == 0 || (i.needs == 1 && (l.app_ext || l.app_fb)) || (i.needs == 2 && l.app_fb);
    if (active && wanted) {
      *function = i.fn;
      return XR_SUCCESS;
    }
    if (i.needs == 2 && active) {  // the FB functions of an instance that did not enable it
      *function = nullptr;
      return XR_ERROR_FUNCTION_UNSUPPORTED;
    }
    break;
  }
  if (std::strcmp(name, "xrGetInstanceProcAddr") == 0) {
    *function = reinterpret_cast<PFN_xrVoidFunction>(layer_xrGetInstanceProcAddr);
    return XR_SUCCESS;
  }
  if (!l.next.GetInstanceProcAddr) return XR_ERROR_HANDLE_INVALID;
  return l.next.GetInstanceProcAddr(instance, name, function);
}

}  // namespace

void decide_serving(XrSystemId system) {
  Layer& l = layer();
  std::lock_guard lock(l.mutex);
  if (l.decided) return;
  bool runtime_gaze = false, runtime_eyes = false;
  XrSystemEyeGazeInteractionPropertiesEXT ext{XR_TYPE_SYSTEM_EYE_GAZE_INTERACTION_PROPERTIES_EXT, nullptr, XR_FALSE};
  XrSystemEyeTrackingPropertiesFB fb{XR_TYPE_SYSTEM_EYE_TRACKING_PROPERTIES_FB, nullptr, XR_FALSE};
  XrSystemProperties props{XR_TYPE_SYSTEM_PROPERTIES, nullptr, 0, 0, {}, {}, {}};
  if (l.runtime_ext) ext.next = props.next, props.next = &ext;
  if (l.runtime_fb) fb.next = props.next, props.next = &fb;
  if (XR_SUCCEEDED(l.next.GetSystemProperties(l.instance, system, &props))) {
    runtime_gaze = l.runtime_ext && ext.supportsEyeGazeInteraction;
    runtime_eyes = l.runtime_fb && fb.supportsEyeTracking;
  }
  const bool always = l.mode == GazeMode::foveal;
  l.serve_ext = l.app_ext && (always || !runtime_gaze);
  l.serve_fb = l.app_fb && (always || !runtime_eyes);
  l.decided = true;
  std::string line = std::string("eye gaze interaction: ") +
                     (!l.app_ext ? "not asked for" : l.serve_ext ? "foveald's" : "the runtime's own") +
                     "; per-eye gaze (XR_FB_eye_tracking_social): " +
                     (!l.app_fb ? "not asked for" : l.serve_fb ? "foveald's" : "the runtime's own");
  log_line(line.c_str());
}

}  // namespace foveal::openxr

extern "C" __attribute__((visibility("default"))) XrResult XRAPI_CALL
xrNegotiateLoaderApiLayerInterface(const XrNegotiateLoaderInfo* loader_info, const char* layer_name,
                                   XrNegotiateApiLayerRequest* request) {
  using namespace foveal::openxr;
  if (!loader_info || !request || loader_info->structType != XR_LOADER_INTERFACE_STRUCT_LOADER_INFO ||
      loader_info->structVersion != XR_LOADER_INFO_STRUCT_VERSION ||
      loader_info->structSize != sizeof(XrNegotiateLoaderInfo) ||
      request->structType != XR_LOADER_INTERFACE_STRUCT_API_LAYER_REQUEST ||
      request->structVersion != XR_API_LAYER_INFO_STRUCT_VERSION ||
      request->structSize != sizeof(XrNegotiateApiLayerRequest))
    return XR_ERROR_INITIALIZATION_FAILED;
  if (layer_name && std::strcmp(layer_name, kLayerName) != 0) return XR_ERROR_INITIALIZATION_FAILED;
  if (loader_info->minInterfaceVersion > XR_CURRENT_LOADER_API_LAYER_VERSION ||
      loader_info->maxInterfaceVersion < XR_CURRENT_LOADER_API_LAYER_VERSION)
    return XR_ERROR_INITIALIZATION_FAILED;
  request->layerInterfaceVersion = XR_CURRENT_LOADER_API_LAYER_VERSION;
  request->layerApiVersion = XR_CURRENT_API_VERSION;
  request->getInstanceProcAddr = layer_xrGetInstanceProcAddr;
  request->createApiLayerInstance = layer_xrCreateApiLayerInstance;
  return XR_SUCCESS;
}

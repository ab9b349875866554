// The layer's entry points: negotiation with the loader, instance creation (which
// extensions go down to the runtime), xrGetInstanceProcAddr over the served extensions'
// table, system properties, and the core calls several extensions share (sessions,
// focus, spaces). docs/openxr.md.
#include "layer.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "loader_interface.h"
#include "locate_spaces.hpp"

namespace foveal::openxr {

Layer& layer() {
  static Layer l;
  return l;
}

namespace {

GazeMode mode_from_environment() {
  const char* v = std::getenv("FOVEAL_OPENXR_GAZE");
  if (!v || !*v || std::string_view(v) == "auto") return GazeMode::automatic;
  if (std::string_view(v) == "foveal") return GazeMode::foveal;
  if (std::string_view(v) == "runtime") return GazeMode::runtime;
  log_line("FOVEAL_OPENXR_GAZE must be auto, foveal or runtime; using auto");
  return GazeMode::automatic;
}

/// FOVEAL_OPENXR_QUAD_VIEWS=0 turns the layer's quad views off for one app.
bool quad_views_wanted() {
  const char* v = std::getenv("FOVEAL_OPENXR_QUAD_VIEWS");
  return !(v && (std::string_view(v) == "0" || std::string_view(v) == "off"));
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

/// The served extension named `name`, or -1.
int served_index(const char* name) {
  for (int e = 0; e < kExtCount; ++e)
    if (std::strcmp(served(static_cast<Ext>(e)).name, name) == 0) return e;
  return -1;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrGetInstanceProcAddr(XrInstance instance, const char* name,
                                                           PFN_xrVoidFunction* function);

void load_next(XrInstance instance, Next& n, bool want_convert) {
  load(instance, "xrDestroyInstance", n.DestroyInstance);
  load(instance, "xrGetSystemProperties", n.GetSystemProperties);
  load(instance, "xrCreateSession", n.CreateSession);
  load(instance, "xrDestroySession", n.DestroySession);
  load(instance, "xrBeginSession", n.BeginSession);
  load(instance, "xrPollEvent", n.PollEvent);
  load(instance, "xrCreateReferenceSpace", n.CreateReferenceSpace);
  load(instance, "xrEnumerateReferenceSpaces", n.EnumerateReferenceSpaces);
  load(instance, "xrCreateActionSpace", n.CreateActionSpace);
  load(instance, "xrDestroySpace", n.DestroySpace);
  load(instance, "xrLocateSpace", n.LocateSpace);
  load(instance, "xrCreateActionSet", n.CreateActionSet);
  load(instance, "xrDestroyActionSet", n.DestroyActionSet);
  load(instance, "xrCreateAction", n.CreateAction);
  load(instance, "xrDestroyAction", n.DestroyAction);
  load(instance, "xrSuggestInteractionProfileBindings", n.SuggestInteractionProfileBindings);
  load(instance, "xrAttachSessionActionSets", n.AttachSessionActionSets);
  load(instance, "xrGetCurrentInteractionProfile", n.GetCurrentInteractionProfile);
  load(instance, "xrSyncActions", n.SyncActions);
  load(instance, "xrGetActionStatePose", n.GetActionStatePose);
  load(instance, "xrStringToPath", n.StringToPath);
  load(instance, "xrEnumerateViewConfigurations", n.EnumerateViewConfigurations);
  load(instance, "xrGetViewConfigurationProperties", n.GetViewConfigurationProperties);
  load(instance, "xrEnumerateViewConfigurationViews", n.EnumerateViewConfigurationViews);
  load(instance, "xrLocateViews", n.LocateViews);
  load(instance, "xrEndFrame", n.EndFrame);
  load(instance, "xrCreateSwapchain", n.CreateSwapchain);
  load(instance, "xrDestroySwapchain", n.DestroySwapchain);
  load(instance, "xrEnumerateSwapchainImages", n.EnumerateSwapchainImages);
  load(instance, "xrAcquireSwapchainImage", n.AcquireSwapchainImage);
  load(instance, "xrWaitSwapchainImage", n.WaitSwapchainImage);
  load(instance, "xrReleaseSwapchainImage", n.ReleaseSwapchainImage);
  if (want_convert) load(instance, "xrConvertTimespecTimeToTimeKHR", n.ConvertTimespecTimeToTimeKHR);
  if (layer().runtime_has(Ext::fb_eye_tracking_social)) {
    load(instance, "xrCreateEyeTrackerFB", n.CreateEyeTrackerFB);
    load(instance, "xrDestroyEyeTrackerFB", n.DestroyEyeTrackerFB);
    load(instance, "xrGetEyeGazesFB", n.GetEyeGazesFB);
  }
}

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

  // The runtime sees the extensions the layer serves only where it has them itself,
  // and gets XR_KHR_convert_timespec_time for the gaze samples' times.
  // Asked of the end of the chain (the runtime): layers below answer only for instances.
  const XrApiLayerNextInfo* last = next_info;
  while (last->next) last = last->next;
  const std::vector<std::string> below = runtime_extensions(last->nextGetInstanceProcAddr);
  std::vector<const char*> enabled;
  for (int e = 0; e < kExtCount; ++e) l.app[e] = l.runtime[e] = false;
  bool want_convert = has(below, XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME);
  const bool pass_all = l.mode == GazeMode::runtime;
  const bool quad_wanted = quad_views_wanted();
  l.instance_1_1 = false;
  l.api_version = 0;
  bool app_locate_spaces_khr = false;  // answered for the layer's spaces, never served (locate_spaces.cpp)
  for (std::uint32_t i = 0; i < info->enabledExtensionCount; ++i) {
    const char* name = info->enabledExtensionNames[i];
    if (std::strcmp(name, XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME) == 0) want_convert = false;  // already there
    if (std::strcmp(name, XR_KHR_LOCATE_SPACES_EXTENSION_NAME) == 0) app_locate_spaces_khr = true;
    const int e = served_index(name);
    if (e >= 0 && !pass_all) {
      const bool quad = e == static_cast<int>(Ext::varjo_quad_views) || e == static_cast<int>(Ext::varjo_foveated_rendering);
      l.app[e] = true;
      l.runtime[e] = has(below, name);
      if (quad && !l.runtime[e] && !quad_wanted) {
        log_line("FOVEAL_OPENXR_QUAD_VIEWS=0: quad views are not offered to this app");
        return XR_ERROR_EXTENSION_NOT_PRESENT;
      }
      if (!l.runtime[e]) continue;  // served by the layer: the runtime never hears of it
    }
    enabled.push_back(name);
  }
  for (int e = 0; e < kExtCount; ++e) {
    const int needs = served(static_cast<Ext>(e)).requires_ext;
    if (l.app[e] && needs >= 0 && !l.app[needs] && !l.runtime[needs]) return XR_ERROR_EXTENSION_NOT_PRESENT;  // 1.0.20 has no DEPENDENCY_NOT_ENABLED
  }
  if (want_convert) enabled.push_back(XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME);

  XrInstanceCreateInfo down = *info;
  down.enabledExtensionCount = static_cast<std::uint32_t>(enabled.size());
  down.enabledExtensionNames = enabled.data();
  XrApiLayerCreateInfo down_layer = *api_layer_info;
  down_layer.nextInfo = next_info->next;
  // The app's apiVersion goes down as it asked: a runtime without that version refuses it
  // (XR_ERROR_API_VERSION_UNSUPPORTED), and the app gets that answer, as without the layer.
  const XrResult r = next_info->nextCreateApiLayerInstance(&down, &down_layer, instance);
  if (XR_FAILED(r)) return r;
  // The runtime accepted the version: for 1.1, the inset view configuration and
  // xrLocateSpaces are core in this instance. (Debian's 1.0 headers lack XR_API_VERSION_1_1.)
  const XrVersion api = info->applicationInfo.apiVersion;
  const bool accepted_1_1 = XR_VERSION_MAJOR(api) == 1 && XR_VERSION_MINOR(api) >= 1;
  l.api_version = api;
  l.instance_1_1 = !pass_all && quad_wanted && accepted_1_1;

  l.instance = *instance;
  l.next = Next{};
  l.next.GetInstanceProcAddr = next_info->nextGetInstanceProcAddr;
  Next& n = l.next;
  load_next(*instance, n, want_convert || has(below, XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME));
  load_locate_spaces(*instance, n.GetInstanceProcAddr, !pass_all && accepted_1_1, !pass_all && app_locate_spaces_khr);
  n.StringToPath(*instance, "/interaction_profiles/ext/eye_gaze_interaction", &l.profile_path);
  n.StringToPath(*instance, "/user/eyes_ext", &l.eyes_path);
  n.StringToPath(*instance, "/user/eyes_ext/input/gaze_ext/pose", &l.gaze_pose_path);
  n.StringToPath(*instance, "/user/eyes_ext/input/gaze_ext", &l.gaze_path);
  l.decided = false;
  l.serve_ext = l.serve_fb = false;
  // Gaze for the action system, per eye, and the quad views' inset all read foveald.
  const bool wants_feed = l.app_gaze() || l.quad_views() || l.app_has(Ext::varjo_foveated_rendering);
  if (!pass_all && wants_feed) {
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
  std::unique_ptr<GazeFeed> feed;
  {
    std::lock_guard lock(l.mutex);
    feed = std::move(l.feed);
    for (auto& a : l.actions) a.handle.store(XR_NULL_HANDLE), a.gaze = false, a.set_active = false;
    for (auto& a : l.attached_sets) a.handle.store(XR_NULL_HANDLE);
    for (auto& s : l.spaces) s.handle.store(XR_NULL_HANDLE);
    for (auto& s : l.sessions) {
      s.handle.store(XR_NULL_HANDLE);
      quad_session_destroyed(s);
    }
    for (auto& t : l.trackers) t.handle.store(XR_NULL_HANDLE);
    l.instance = XR_NULL_HANDLE;
  }
  // Its thread converts times through the instance: stopped first, outside the mutex
  // (it wakes at once: the thread waits on a condition, never on the app).
  feed.reset();
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
  if (!props) return l.next.GetSystemProperties(instance, system, props);
  decide_serving(system);
  XrBaseOutStructure* taken[kExtCount] = {};
  for (int e = 0; e < kExtCount; ++e) {
    const ServedExtension& x = served(static_cast<Ext>(e));
    if (x.system_properties_type != 0 && l.app[e] && !l.runtime[e]) taken[e] = unlink(props, x.system_properties_type);
  }
  const XrResult r = l.next.GetSystemProperties(instance, system, props);
  for (int e = kExtCount - 1; e >= 0; --e) restore(taken[e]);
  if (XR_FAILED(r)) return r;
  for (auto* p = reinterpret_cast<XrBaseOutStructure*>(props->next); p; p = p->next)
    for (int e = 0; e < kExtCount; ++e) {
      const ServedExtension& x = served(static_cast<Ext>(e));
      if (l.app[e] && p->type == x.system_properties_type && x.fill_system_properties) x.fill_system_properties(p);
    }
  return r;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrCreateSession(XrInstance instance, const XrSessionCreateInfo* info,
                                                     XrSession* session) {
  Layer& l = layer();
  const XrResult r = l.next.CreateSession(instance, info, session);
  if (XR_FAILED(r)) return r;
  decide_serving(info->systemId);
  std::lock_guard lock(l.mutex);
  XrReferenceSpaceCreateInfo view_info{XR_TYPE_REFERENCE_SPACE_CREATE_INFO, nullptr, XR_REFERENCE_SPACE_TYPE_VIEW,
                                       {{0, 0, 0, 1}, {0, 0, 0}}};
  XrSpace view = XR_NULL_HANDLE;
  if (XR_FAILED(l.next.CreateReferenceSpace(*session, &view_info, &view))) {
    log_line("the runtime refused a VIEW space: no eye gaze or quad views in this session");
    return r;
  }
  const bool claimed = claim_slot(l.sessions, *session, [&](SessionSlot& slot) {
    slot.view = view;
    slot.focused = false;
    slot.gaze_active = false;
    slot.app_reads_gaze = false;
    slot.latched.store(false, GazeNow{});
    slot.system = info->systemId;
    quad_session_created(slot, info);
  });
  if (!claimed) {
    l.next.DestroySpace(view);
    log_line("more than 4 sessions at once: no eye gaze or quad views in this one");
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
      quad_session_destroyed(*s);
    }
    for (auto& t : l.trackers)
      if (t.handle.load() == session) t.handle.store(XR_NULL_HANDLE);
    for (auto& sp : l.spaces)
      if (sp.handle.load() != XR_NULL_HANDLE && sp.session == session) sp.handle.store(XR_NULL_HANDLE);
    for (auto& a : l.attached_sets)
      if (a.handle.load() != XR_NULL_HANDLE && a.session == session) a.handle.store(XR_NULL_HANDLE);
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

XRAPI_ATTR XrResult XRAPI_CALL layer_xrDestroySpace(XrSpace space) {
  Layer& l = layer();
  {
    std::lock_guard lock(l.mutex);
    if (SpaceSlot* s = find_space(space)) s->handle.store(XR_NULL_HANDLE);
  }
  return l.next.DestroySpace(space);
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrLocateSpace(XrSpace space, XrSpace base, XrTime time,
                                                   XrSpaceLocation* location) {
  return locate_space(space, base, time, location);
}

/// The calls the layer always answers for an instance that enabled any served extension.
const Intercept kCore[] = {
    {"xrDestroyInstance", FOVEAL_FN(layer_xrDestroyInstance), false},
    {"xrGetSystemProperties", FOVEAL_FN(layer_xrGetSystemProperties), false},
    {"xrCreateSession", FOVEAL_FN(layer_xrCreateSession), false},
    {"xrDestroySession", FOVEAL_FN(layer_xrDestroySession), false},
    {"xrPollEvent", FOVEAL_FN(layer_xrPollEvent), false},
    {"xrDestroySpace", FOVEAL_FN(layer_xrDestroySpace), false},
    {"xrLocateSpace", FOVEAL_FN(layer_xrLocateSpace), false},
};

XRAPI_ATTR XrResult XRAPI_CALL layer_xrGetInstanceProcAddr(XrInstance instance, const char* name,
                                                           PFN_xrVoidFunction* function) {
  Layer& l = layer();
  if (!name || !function) return XR_ERROR_VALIDATION_FAILURE;
  if (std::strcmp(name, "xrGetInstanceProcAddr") == 0) {
    *function = reinterpret_cast<PFN_xrVoidFunction>(layer_xrGetInstanceProcAddr);
    return XR_SUCCESS;
  }
  // In pass-through mode, or for an app that asked for nothing the layer serves, the
  // layer is not there.
  const bool active = l.mode != GazeMode::runtime && instance != XR_NULL_HANDLE && instance == l.instance;
  bool any = l.quad_views();
  for (int e = 0; e < kExtCount; ++e) any |= l.app[e];
  if (active && any) {
    for (const Intercept& i : kCore)
      if (std::strcmp(name, i.name) == 0) return *function = i.fn, XR_SUCCESS;
    if (PFN_xrVoidFunction f = locate_spaces_function(name)) return *function = f, XR_SUCCESS;
    for (int e = 0; e < kExtCount; ++e) {
      const ServedExtension& x = served(static_cast<Ext>(e));
      // The 1.1 inset configuration needs quad views' calls without the extension.
      const bool on = l.app[e] || (e == static_cast<int>(Ext::varjo_quad_views) && l.instance_1_1);
      for (std::size_t k = 0; k < x.function_count; ++k) {
        const Intercept& i = x.functions[k];
        if (std::strcmp(name, i.name) != 0) continue;
        if (on) return *function = i.fn, XR_SUCCESS;
        if (i.extension_only && !l.runtime[e]) return *function = nullptr, XR_ERROR_FUNCTION_UNSUPPORTED;
      }
    }
  }
  if (!l.next.GetInstanceProcAddr) return XR_ERROR_HANDLE_INVALID;
  return l.next.GetInstanceProcAddr(instance, name, function);
}

}  // namespace

// A COMBINED_EYE_VARJO space (action < 0) or an eye-gaze action space, on either side.
XrResult locate_space(XrSpace space, XrSpace base, XrTime time, XrSpaceLocation* location) {
  Layer& l = layer();
  if (!location) return l.next.LocateSpace(space, base, time, location);
  const SpaceSlot* sp = find_space(space);
  const SpaceSlot* bp = find_space(base);
  if ((sp && sp->action < 0) || (bp && bp->action < 0))
    return locate_combined_eye_space(space, base, time, location, sp, bp);
  if (is_gaze_action_space(sp) || is_gaze_action_space(bp))
    return locate_gaze_action_space(space, base, time, location, sp, bp);
  return l.next.LocateSpace(space, base, time, location);
}

bool layer_locates(XrSpace space) {
  const SpaceSlot* s = find_space(space);
  return (s && s->action < 0) || is_gaze_action_space(s);
}

void decide_serving(XrSystemId system) {
  Layer& l = layer();
  std::lock_guard lock(l.mutex);
  if (l.decided) return;
  bool runtime_gaze = false, runtime_eyes = false;
  const bool runtime_ext = l.runtime_has(Ext::eye_gaze_interaction), runtime_fb = l.runtime_has(Ext::fb_eye_tracking_social);
  XrSystemEyeGazeInteractionPropertiesEXT ext{XR_TYPE_SYSTEM_EYE_GAZE_INTERACTION_PROPERTIES_EXT, nullptr, XR_FALSE};
  XrSystemEyeTrackingPropertiesFB fb{XR_TYPE_SYSTEM_EYE_TRACKING_PROPERTIES_FB, nullptr, XR_FALSE};
  XrSystemProperties props{XR_TYPE_SYSTEM_PROPERTIES, nullptr, 0, 0, {}, {}, {}};
  if (runtime_ext) ext.next = props.next, props.next = &ext;
  if (runtime_fb) fb.next = props.next, props.next = &fb;
  if (XR_SUCCEEDED(l.next.GetSystemProperties(l.instance, system, &props))) {
    runtime_gaze = runtime_ext && ext.supportsEyeGazeInteraction;
    runtime_eyes = runtime_fb && fb.supportsEyeTracking;
  }
  const bool always = l.mode == GazeMode::foveal;
  const bool app_ext = l.app_has(Ext::eye_gaze_interaction), app_fb = l.app_has(Ext::fb_eye_tracking_social);
  l.serve_ext = app_ext && (always || !runtime_gaze);
  l.serve_fb = app_fb && (always || !runtime_eyes);
  l.decided = true;
  std::string line = std::string("eye gaze interaction: ") +
                     (!app_ext ? "not asked for" : l.serve_ext ? "foveald's" : "the runtime's own") +
                     "; per-eye gaze (XR_FB_eye_tracking_social): " +
                     (!app_fb ? "not asked for" : l.serve_fb ? "foveald's" : "the runtime's own") +
                     "; quad views: " + (l.quad_views() ? "the layer's, following foveald's gaze" : "not asked for");
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

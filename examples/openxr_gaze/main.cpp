// openxr_gaze: a headless OpenXR application that reads eye gaze the way any app does,
// and prints it as JSON lines. It knows nothing of foveal: with foveal's API layer
// installed and foveald running, the gaze it prints is foveald's (docs/openxr.md).
//
//   openxr_gaze [--duration S] [--interval-ms MS] [--per-eye] [--frame-loop] [--bench N]
//               [--second-set] [--ahead-ms MS] [--api MAJOR.MINOR] [--locate-spaces] [--help]
//
// Line 1: {"event":"system", ...} what the runtime (and the layers) offer, with the
// instance's "api_version" and the system's "view_configurations"; or, where the runtime
// refuses the instance, {"event":"instance","result":N} (N the XrResult) and exit 1.
// Then, every interval: {"event":"gaze", "t_ns":..., "state":..., "active":...,
//   "flags":..., "view_flags":... (the gaze located in LOCAL and in VIEW), "head_direction":[x,y,z] (the gaze in the VIEW space: the head frame),
//   "direction":[x,y,z] (in LOCAL), "sample_t_ns" (head_direction's sample), "local_sample_t_ns"}
//   and with --per-eye "eyes":[...] with their own "eyes_t_ns".
//   With --locate-spaces, the same reading also locates [gaze, VIEW] in LOCAL and
//   [LOCAL] in the gaze space through xrLocateSpaces (OpenXR 1.1) or xrLocateSpacesKHR,
//   beside xrLocateSpace's answers for the same pairs at the same time: "single" and
//   "spaces", each {"gaze","view","local_in_gaze"} as {"flags","orientation","position"}.
// --bench N: once the gaze is active, times N locates of the gaze space and N of the
// VIEW space (the runtime's own work the layer's gaze locate includes), interleaved, and
// prints {"event":"bench",...} with their percentiles.
// Times are CLOCK_MONOTONIC ns (converted from XrTime with XR_KHR_convert_timespec_time).
#include <time.h>

#define XR_USE_TIMESPEC  // XR_KHR_convert_timespec_time
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "foveal/openxr/fb_eye_tracking_social.h"
#include "foveal/openxr/locate_spaces.h"

namespace {

struct Options {
  double duration_s = 10.0;
  int interval_ms = 10;
  bool per_eye = false;
  bool frame_loop = false;
  int bench = 0;
  bool second_set = false;
  int ahead_ms = 0;
  XrVersion api = XR_MAKE_VERSION(1, 0, 0);
  bool locate_spaces = false;
};

/// "1.1" -> XR_MAKE_VERSION(1, 1, 0); false for anything else.
bool parse_api(const char* text, XrVersion& out) {
  unsigned major = 0, minor = 0;
  char end = 0;
  if (std::sscanf(text, "%u.%u%c", &major, &minor, &end) != 2 || major < 1 || major > 0xffff || minor > 0xffff)
    return false;
  out = XR_MAKE_VERSION(major, minor, 0);
  return true;
}

int usage(int rc) {
  std::fprintf(rc ? stderr : stdout,
               "usage: openxr_gaze [--duration S] [--interval-ms MS] [--per-eye] [--frame-loop]\n"
               "                   [--ahead-ms MS] [--bench N] [--second-set] [--api MAJOR.MINOR] [--locate-spaces]\n"
               "  Reads eye gaze through OpenXR (XR_EXT_eye_gaze_interaction; with --per-eye also\n"
               "  XR_FB_eye_tracking_social) in a headless session and prints JSON lines.\n"
               "  --frame-loop: run xrWaitFrame/xrBeginFrame/xrEndFrame and locate at the predicted\n"
               "  display time (default: locate at the current time; Monado's headless sessions have no\n"
               "  frame loop).\n"
               "  --ahead-ms MS: locate MS ahead of the current time, as at a frame's predicted display\n"
               "  time (0-1000; foveal's layer predicts the gaze there).\n"
               "  --bench N: time N gaze-space and N VIEW-space locates once the gaze is active.\n"
               "  --second-set: after the session, bind the gaze to a new action set (a next session's).\n"
               "  --api MAJOR.MINOR: the OpenXR version the instance asks for (default 1.0; 1.1 makes the\n"
               "  inset view configuration and xrLocateSpaces core). A runtime without it refuses the\n"
               "  instance: the program prints {\"event\":\"instance\",\"result\":N} and exits 1.\n"
               "  --locate-spaces: in each reading, also locate the gaze and VIEW spaces through\n"
               "  xrLocateSpaces (--api 1.1) or xrLocateSpacesKHR (XR_KHR_locate_spaces), beside\n"
               "  xrLocateSpace at the same time.\n");
  return rc;
}

// CHECK_R: the same inside a lambda that returns an int.
#define CHECK_R(call)                                                                     \
  do {                                                                                    \
    const XrResult r_ = (call);                                                           \
    if (XR_FAILED(r_)) {                                                                  \
      std::fprintf(stderr, "openxr_gaze: %s failed: %d\n", #call, (int)r_);              \
      return 1;                                                                           \
    }                                                                                     \
  } while (0)

#define CHECK(call)                                                                       \
  do {                                                                                    \
    const XrResult r_ = (call);                                                           \
    if (XR_FAILED(r_)) {                                                                  \
      char name_[XR_MAX_RESULT_STRING_SIZE] = "?";                                        \
      if (instance != XR_NULL_HANDLE) xrResultToString(instance, r_, name_);              \
      std::fprintf(stderr, "openxr_gaze: %s failed: %s (%d)\n", #call, name_, (int)r_);   \
      return 1;                                                                           \
    }                                                                                     \
  } while (0)

XrInstance instance = XR_NULL_HANDLE;
PFN_xrConvertTimespecTimeToTimeKHR to_xr = nullptr;
PFN_xrConvertTimeToTimespecTimeKHR from_xr = nullptr;

std::int64_t monotonic_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

XrTime xr_now() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  XrTime t = 0;
  if (to_xr) to_xr(instance, &ts, &t);
  return t;
}

std::int64_t mono_of(XrTime t) {
  timespec ts{};
  if (!from_xr || t <= 0 || XR_FAILED(from_xr(instance, t, &ts))) return 0;
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

/// "name":{"flags":F,"orientation":[x,y,z,w],"position":[x,y,z]}, exact to the float.
void print_location(const char* name, XrSpaceLocationFlags flags, const XrPosef& p) {
  std::printf("\"%s\":{\"flags\":%llu,\"orientation\":[%.9g,%.9g,%.9g,%.9g],\"position\":[%.9g,%.9g,%.9g]}", name,
              (unsigned long long)flags, p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w,
              p.position.x, p.position.y, p.position.z);
}

XrVector3f forward(const XrQuaternionf& q) {  // the pose's -z axis
  return {-2 * (q.x * q.z + q.w * q.y), -2 * (q.y * q.z - q.w * q.x), -(1 - 2 * (q.x * q.x + q.y * q.y))};
}

const char* state_name(XrSessionState s) {
  switch (s) {
    case XR_SESSION_STATE_IDLE: return "IDLE";
    case XR_SESSION_STATE_READY: return "READY";
    case XR_SESSION_STATE_SYNCHRONIZED: return "SYNCHRONIZED";
    case XR_SESSION_STATE_VISIBLE: return "VISIBLE";
    case XR_SESSION_STATE_FOCUSED: return "FOCUSED";
    case XR_SESSION_STATE_STOPPING: return "STOPPING";
    case XR_SESSION_STATE_LOSS_PENDING: return "LOSS_PENDING";
    case XR_SESSION_STATE_EXITING: return "EXITING";
    default: return "UNKNOWN";
  }
}

std::int64_t percentile(std::vector<std::int64_t> v, double p) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1))];
}

/// The gaze space's locate against the runtime's own locate of the VIEW space, interleaved.
void bench(XrSpace gaze, XrSpace view, XrSpace base, XrTime when, int n) {
  std::vector<std::int64_t> g, v;
  g.reserve(static_cast<std::size_t>(n));
  v.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    XrEyeGazeSampleTimeEXT sample{XR_TYPE_EYE_GAZE_SAMPLE_TIME_EXT};
    XrSpaceLocation loc{XR_TYPE_SPACE_LOCATION, &sample};
    std::int64_t t0 = monotonic_ns();
    xrLocateSpace(gaze, base, when, &loc);
    std::int64_t t1 = monotonic_ns();
    g.push_back(t1 - t0);
    XrSpaceLocation head{XR_TYPE_SPACE_LOCATION};
    t0 = monotonic_ns();
    xrLocateSpace(view, base, when, &head);
    t1 = monotonic_ns();
    v.push_back(t1 - t0);
  }
  std::printf("{\"event\":\"bench\",\"calls\":%d", n);
  for (auto [name, d] : {std::pair<const char*, std::vector<std::int64_t>*>{"gaze_locate_ns", &g}, {"view_locate_ns", &v}})
    std::printf(",\"%s\":{\"p50\":%lld,\"p99\":%lld,\"max\":%lld}", name, (long long)percentile(*d, 0.5),
                (long long)percentile(*d, 0.99), (long long)percentile(*d, 1.0));
  std::printf(",\"added_ns\":{\"p50\":%lld,\"p99\":%lld}}\n", (long long)(percentile(g, 0.5) - percentile(v, 0.5)),
              (long long)(percentile(g, 0.99) - percentile(v, 0.99)));
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const char* what) -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "openxr_gaze: %s needs a value\n", what);
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--help" || a == "-h") return usage(0);
    if (a == "--duration") o.duration_s = std::atof(value("--duration"));
    else if (a == "--interval-ms") o.interval_ms = std::atoi(value("--interval-ms"));
    else if (a == "--per-eye") o.per_eye = true;
    else if (a == "--frame-loop") o.frame_loop = true;
    else if (a == "--bench") o.bench = std::atoi(value("--bench"));
    else if (a == "--second-set") o.second_set = true;
    else if (a == "--ahead-ms") o.ahead_ms = std::atoi(value("--ahead-ms"));
    else if (a == "--api") {
      const char* v = value("--api");
      if (!parse_api(v, o.api)) {
        std::fprintf(stderr, "openxr_gaze: --api takes MAJOR.MINOR (1.0, 1.1), not %s\n", v);
        return 2;
      }
    } else if (a == "--locate-spaces") o.locate_spaces = true;
    else {
      std::fprintf(stderr, "openxr_gaze: unknown option %s\n", a.c_str());
      return usage(2);
    }
  }
  if (!(o.duration_s > 0) || o.interval_ms < 1 || o.bench < 0 || o.ahead_ms < 0 || o.ahead_ms > 1000) {
    std::fprintf(stderr, "openxr_gaze: --duration must be > 0, --interval-ms >= 1, --bench >= 0 and --ahead-ms 0-1000\n");
    return 2;
  }

  // What the loader offers: the runtime's extensions and those of the enabled layers.
  std::uint32_t n = 0;
  CHECK(xrEnumerateInstanceExtensionProperties(nullptr, 0, &n, nullptr));
  std::vector<XrExtensionProperties> props(n, {XR_TYPE_EXTENSION_PROPERTIES, nullptr, {}, 0});
  CHECK(xrEnumerateInstanceExtensionProperties(nullptr, n, &n, props.data()));
  auto offered = [&](const char* name) {
    for (const auto& p : props)
      if (std::strcmp(p.extensionName, name) == 0) return true;
    return false;
  };
  std::vector<const char*> wanted;
  for (const char* e : {XR_MND_HEADLESS_EXTENSION_NAME, XR_EXT_EYE_GAZE_INTERACTION_EXTENSION_NAME,
                        XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME})
    if (offered(e)) wanted.push_back(e);
  const bool has_fb = o.per_eye && offered(XR_FB_EYE_TRACKING_SOCIAL_EXTENSION_NAME);
  if (has_fb) wanted.push_back(XR_FB_EYE_TRACKING_SOCIAL_EXTENSION_NAME);
  // xrLocateSpaces: core from 1.1, else XR_KHR_locate_spaces where the runtime offers it.
  const bool core_1_1 = XR_VERSION_MAJOR(o.api) > 1 || XR_VERSION_MINOR(o.api) >= 1;
  const bool use_khr = o.locate_spaces && !core_1_1 && offered(XR_KHR_LOCATE_SPACES_EXTENSION_NAME);
  if (use_khr) wanted.push_back(XR_KHR_LOCATE_SPACES_EXTENSION_NAME);
  if (o.locate_spaces && !core_1_1 && !use_khr) {
    std::fprintf(stderr, "openxr_gaze: --locate-spaces needs --api 1.1 or a runtime with XR_KHR_locate_spaces\n");
    return 1;
  }
  const bool has_gaze_ext = offered(XR_EXT_EYE_GAZE_INTERACTION_EXTENSION_NAME);
  if (!offered(XR_MND_HEADLESS_EXTENSION_NAME)) {
    std::fprintf(stderr, "openxr_gaze: the runtime has no XR_MND_headless: this example runs headless only\n");
    return 1;
  }

  XrInstanceCreateInfo ci{XR_TYPE_INSTANCE_CREATE_INFO};
  std::snprintf(ci.applicationInfo.applicationName, XR_MAX_APPLICATION_NAME_SIZE, "openxr_gaze");
  ci.applicationInfo.apiVersion = o.api;
  ci.enabledExtensionCount = static_cast<std::uint32_t>(wanted.size());
  ci.enabledExtensionNames = wanted.data();
  if (const XrResult r = xrCreateInstance(&ci, &instance); XR_FAILED(r)) {
    // XR_ERROR_API_VERSION_UNSUPPORTED (-4): the runtime has no such version.
    std::printf("{\"event\":\"instance\",\"result\":%d}\n", (int)r);
    std::fprintf(stderr, "openxr_gaze: xrCreateInstance (apiVersion %u.%u) failed: %d\n", XR_VERSION_MAJOR(o.api),
                 XR_VERSION_MINOR(o.api), (int)r);
    return 1;
  }
  PFN_xrLocateSpaces locate_spaces = nullptr;
  if (o.locate_spaces)
    CHECK(xrGetInstanceProcAddr(instance, use_khr ? "xrLocateSpacesKHR" : "xrLocateSpaces",
                                reinterpret_cast<PFN_xrVoidFunction*>(&locate_spaces)));
  xrGetInstanceProcAddr(instance, "xrConvertTimespecTimeToTimeKHR", reinterpret_cast<PFN_xrVoidFunction*>(&to_xr));
  xrGetInstanceProcAddr(instance, "xrConvertTimeToTimespecTimeKHR", reinterpret_cast<PFN_xrVoidFunction*>(&from_xr));

  XrSystemGetInfo sgi{XR_TYPE_SYSTEM_GET_INFO, nullptr, XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY};
  XrSystemId system = XR_NULL_SYSTEM_ID;
  CHECK(xrGetSystem(instance, &sgi, &system));
  XrSystemEyeTrackingPropertiesFB fb_props{XR_TYPE_SYSTEM_EYE_TRACKING_PROPERTIES_FB, nullptr, XR_FALSE};
  XrSystemEyeGazeInteractionPropertiesEXT gaze_props{XR_TYPE_SYSTEM_EYE_GAZE_INTERACTION_PROPERTIES_EXT,
                                                     has_fb ? &fb_props : nullptr, XR_FALSE};
  void* chain = has_gaze_ext ? static_cast<void*>(&gaze_props) : has_fb ? static_cast<void*>(&fb_props) : nullptr;
  XrSystemProperties sp{XR_TYPE_SYSTEM_PROPERTIES, chain};
  CHECK(xrGetSystemProperties(instance, system, &sp));
  XrInstanceProperties ip{XR_TYPE_INSTANCE_PROPERTIES};
  CHECK(xrGetInstanceProperties(instance, &ip));
  std::uint32_t nv = 0;
  CHECK(xrEnumerateViewConfigurations(instance, system, 0, &nv, nullptr));
  std::vector<XrViewConfigurationType> configs(nv);
  CHECK(xrEnumerateViewConfigurations(instance, system, nv, &nv, configs.data()));
  std::printf("{\"event\":\"system\",\"api_version\":\"%u.%u\",\"locate_spaces\":\"%s\",\"view_configurations\":[",
              XR_VERSION_MAJOR(o.api), XR_VERSION_MINOR(o.api),
              !o.locate_spaces ? "" : use_khr ? "xrLocateSpacesKHR" : "xrLocateSpaces");
  for (std::uint32_t i = 0; i < nv; ++i) std::printf("%s%d", i ? "," : "", (int)configs[i]);
  std::printf("],\"runtime\":\"%s\",\"system\":\"%s\",\"eye_gaze_interaction\":%s,"
              "\"supportsEyeGazeInteraction\":%d,\"eye_tracking_social\":%s,\"supportsEyeTracking\":%d,\"extensions\":[",
              ip.runtimeName, sp.systemName, has_gaze_ext ? "true" : "false", (int)gaze_props.supportsEyeGazeInteraction,
              has_fb ? "true" : "false", (int)fb_props.supportsEyeTracking);
  for (std::size_t i = 0; i < props.size(); ++i) std::printf("%s\"%s\"", i ? "," : "", props[i].extensionName);
  std::uint32_t nl = 0;
  CHECK(xrEnumerateApiLayerProperties(0, &nl, nullptr));
  std::vector<XrApiLayerProperties> layers(nl, {XR_TYPE_API_LAYER_PROPERTIES, nullptr, {}, 0, 0, {}});
  CHECK(xrEnumerateApiLayerProperties(nl, &nl, layers.data()));
  std::printf("],\"api_layers\":[");
  for (std::uint32_t i = 0; i < nl; ++i) std::printf("%s\"%s\"", i ? "," : "", layers[i].layerName);
  std::printf("]}\n");
  std::fflush(stdout);
  if (!has_gaze_ext) {
    std::fprintf(stderr, "openxr_gaze: XR_EXT_eye_gaze_interaction is not offered: no gaze to read\n");
    xrDestroyInstance(instance);
    return 3;
  }

  // The eye-gaze action, bound as the extension describes.
  XrActionSetCreateInfo asci{XR_TYPE_ACTION_SET_CREATE_INFO};
  std::strcpy(asci.actionSetName, "gaze");
  std::strcpy(asci.localizedActionSetName, "Gaze");
  XrActionSet set = XR_NULL_HANDLE;
  CHECK(xrCreateActionSet(instance, &asci, &set));
  XrActionCreateInfo aci{XR_TYPE_ACTION_CREATE_INFO};
  aci.actionType = XR_ACTION_TYPE_POSE_INPUT;
  std::strcpy(aci.actionName, "gaze_pose");
  std::strcpy(aci.localizedActionName, "Gaze pose");
  XrAction gaze_action = XR_NULL_HANDLE;
  CHECK(xrCreateAction(set, &aci, &gaze_action));
  XrPath profile = XR_NULL_PATH, binding = XR_NULL_PATH;
  CHECK(xrStringToPath(instance, "/interaction_profiles/ext/eye_gaze_interaction", &profile));
  CHECK(xrStringToPath(instance, "/user/eyes_ext/input/gaze_ext/pose", &binding));
  XrActionSuggestedBinding b{gaze_action, binding};
  XrInteractionProfileSuggestedBinding sb{XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING, nullptr, profile, 1, &b};
  CHECK(xrSuggestInteractionProfileBindings(instance, &sb));

  XrSessionCreateInfo sci{XR_TYPE_SESSION_CREATE_INFO, nullptr, 0, system};  // XR_MND_headless: no graphics binding
  XrSession session = XR_NULL_HANDLE;
  CHECK(xrCreateSession(instance, &sci, &session));
  XrSessionActionSetsAttachInfo attach{XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO, nullptr, 1, &set};
  CHECK(xrAttachSessionActionSets(session, &attach));
  XrActionSpaceCreateInfo space_ci{XR_TYPE_ACTION_SPACE_CREATE_INFO, nullptr, gaze_action, XR_NULL_PATH,
                                   {{0, 0, 0, 1}, {0, 0, 0}}};
  XrSpace gaze_space = XR_NULL_HANDLE, local = XR_NULL_HANDLE, view = XR_NULL_HANDLE;
  CHECK(xrCreateActionSpace(session, &space_ci, &gaze_space));
  XrReferenceSpaceCreateInfo rci{XR_TYPE_REFERENCE_SPACE_CREATE_INFO, nullptr, XR_REFERENCE_SPACE_TYPE_LOCAL,
                                 {{0, 0, 0, 1}, {0, 0, 0}}};
  CHECK(xrCreateReferenceSpace(session, &rci, &local));
  rci.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_VIEW;
  CHECK(xrCreateReferenceSpace(session, &rci, &view));

  XrEyeTrackerFB tracker = XR_NULL_HANDLE;
  PFN_xrCreateEyeTrackerFB create_tracker = nullptr;
  PFN_xrDestroyEyeTrackerFB destroy_tracker = nullptr;
  PFN_xrGetEyeGazesFB get_gazes = nullptr;
  if (has_fb) {
    CHECK(xrGetInstanceProcAddr(instance, "xrCreateEyeTrackerFB", reinterpret_cast<PFN_xrVoidFunction*>(&create_tracker)));
    CHECK(xrGetInstanceProcAddr(instance, "xrDestroyEyeTrackerFB", reinterpret_cast<PFN_xrVoidFunction*>(&destroy_tracker)));
    CHECK(xrGetInstanceProcAddr(instance, "xrGetEyeGazesFB", reinterpret_cast<PFN_xrVoidFunction*>(&get_gazes)));
    XrEyeTrackerCreateInfoFB tci{XR_TYPE_EYE_TRACKER_CREATE_INFO_FB, nullptr};
    CHECK(create_tracker(session, &tci, &tracker));
  }

  XrSessionState state = XR_SESSION_STATE_UNKNOWN;
  bool running = false;
  // One reading of the gaze, as an app does it each frame: sync, state, locate.
  auto read_gaze = [&](XrTime when) -> int {
    XrActiveActionSet active{set, XR_NULL_PATH};
    XrActionsSyncInfo si{XR_TYPE_ACTIONS_SYNC_INFO, nullptr, 1, &active};
    const XrResult sync = xrSyncActions(session, &si);
    XrActionStateGetInfo gi{XR_TYPE_ACTION_STATE_GET_INFO, nullptr, gaze_action, XR_NULL_PATH};
    XrActionStatePose pose_state{XR_TYPE_ACTION_STATE_POSE};
    CHECK_R(xrGetActionStatePose(session, &gi, &pose_state));
    XrEyeGazeSampleTimeEXT sample{XR_TYPE_EYE_GAZE_SAMPLE_TIME_EXT};
    XrSpaceLocation in_local{XR_TYPE_SPACE_LOCATION, &sample};
    CHECK_R(xrLocateSpace(gaze_space, local, when, &in_local));
    XrEyeGazeSampleTimeEXT sample_view{XR_TYPE_EYE_GAZE_SAMPLE_TIME_EXT};
    XrSpaceLocation in_view{XR_TYPE_SPACE_LOCATION, &sample_view};
    CHECK_R(xrLocateSpace(gaze_space, view, when, &in_view));
    const XrVector3f d = forward(in_local.pose.orientation), h = forward(in_view.pose.orientation);
    std::printf("{\"event\":\"gaze\",\"t_ns\":%lld,\"state\":\"%s\",\"sync\":%d,\"active\":%s,\"flags\":%llu,"
                "\"view_flags\":%llu,"
                "\"head_direction\":[%.6f,%.6f,%.6f],\"direction\":[%.6f,%.6f,%.6f],\"position\":[%.6f,%.6f,%.6f],"
                "\"sample_t_ns\":%lld,\"local_sample_t_ns\":%lld",
                (long long)mono_of(when), state_name(state), (int)sync, pose_state.isActive ? "true" : "false",
                (unsigned long long)in_local.locationFlags, (unsigned long long)in_view.locationFlags, h.x, h.y, h.z, d.x, d.y, d.z, in_local.pose.position.x,
                in_local.pose.position.y, in_local.pose.position.z, (long long)mono_of(sample_view.time),
                (long long)mono_of(sample.time));
    if (locate_spaces) {
      // The same pairs at the same time, one xrLocateSpace each and through xrLocateSpaces:
      // [gaze, VIEW] in LOCAL (velocities asked for too), and LOCAL in the gaze space.
      XrSpaceLocation view_one{XR_TYPE_SPACE_LOCATION}, local_one{XR_TYPE_SPACE_LOCATION};
      CHECK_R(xrLocateSpace(view, local, when, &view_one));
      CHECK_R(xrLocateSpace(local, gaze_space, when, &local_one));
      const XrSpace pair[2] = {gaze_space, view};
      XrSpaceLocationData data[2] = {};
      XrSpaceVelocityData vel[2] = {};
      XrSpaceVelocities velocities{XR_TYPE_SPACE_VELOCITIES, nullptr, 2, vel};
      XrSpaceLocations many{XR_TYPE_SPACE_LOCATIONS, &velocities, 2, data};
      const XrSpacesLocateInfo in_local_info{XR_TYPE_SPACES_LOCATE_INFO, nullptr, local, when, 2, pair};
      CHECK_R(locate_spaces(session, &in_local_info, &many));
      XrSpaceLocationData local_data[1] = {};
      XrSpaceLocations in_gaze{XR_TYPE_SPACE_LOCATIONS, nullptr, 1, local_data};
      const XrSpacesLocateInfo in_gaze_info{XR_TYPE_SPACES_LOCATE_INFO, nullptr, gaze_space, when, 1, &local};
      CHECK_R(locate_spaces(session, &in_gaze_info, &in_gaze));
      std::printf(",\"single\":{");
      print_location("gaze", in_local.locationFlags, in_local.pose);
      std::printf(",");
      print_location("view", view_one.locationFlags, view_one.pose);
      std::printf(",");
      print_location("local_in_gaze", local_one.locationFlags, local_one.pose);
      std::printf("},\"spaces\":{");
      print_location("gaze", data[0].locationFlags, data[0].pose);
      std::printf(",");
      print_location("view", data[1].locationFlags, data[1].pose);
      std::printf(",");
      print_location("local_in_gaze", local_data[0].locationFlags, local_data[0].pose);
      std::printf(",\"velocity_flags\":[%llu,%llu]}", (unsigned long long)vel[0].velocityFlags,
                  (unsigned long long)vel[1].velocityFlags);
    }
    if (has_fb) {
      XrEyeGazesInfoFB gi_fb{XR_TYPE_EYE_GAZES_INFO_FB, nullptr, view, when};
      XrEyeGazesFB gazes{XR_TYPE_EYE_GAZES_FB};
      CHECK_R(get_gazes(tracker, &gi_fb, &gazes));
      std::printf(",\"eyes_t_ns\":%lld,\"eyes\":[", (long long)mono_of(gazes.time));
      for (int e = 0; e < 2; ++e) {
        const XrEyeGazeFB& g = gazes.gaze[e];
        const XrVector3f f = forward(g.gazePose.orientation);
        std::printf("%s{\"valid\":%s,\"confidence\":%.4f,\"direction\":[%.6f,%.6f,%.6f],\"position\":[%.6f,%.6f,%.6f]}",
                    e ? "," : "", g.isValid ? "true" : "false", g.gazeConfidence, f.x, f.y, f.z,
                    g.gazePose.position.x, g.gazePose.position.y, g.gazePose.position.z);
      }
      std::printf("]");
    }
    std::printf("}\n");
    std::fflush(stdout);
    if (o.bench > 0 && pose_state.isActive) {
      bench(gaze_space, view, local, when, o.bench);
      o.bench = 0;
    }
    return 0;
  };
  const std::int64_t end = monotonic_ns() + static_cast<std::int64_t>(o.duration_s * 1e9);
  while (monotonic_ns() < end) {
    XrEventDataBuffer ev{XR_TYPE_EVENT_DATA_BUFFER};
    while (xrPollEvent(instance, &ev) == XR_SUCCESS) {
      if (ev.type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) {
        state = reinterpret_cast<XrEventDataSessionStateChanged*>(&ev)->state;
        std::printf("{\"event\":\"state\",\"t_ns\":%lld,\"state\":\"%s\"}\n", (long long)monotonic_ns(), state_name(state));
        if (state == XR_SESSION_STATE_READY && !running) {
          XrSessionBeginInfo bi{XR_TYPE_SESSION_BEGIN_INFO, nullptr, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO};
          CHECK(xrBeginSession(session, &bi));
          running = true;
        }
      }
      ev = {XR_TYPE_EVENT_DATA_BUFFER};
    }
    XrTime when = xr_now() + static_cast<XrTime>(o.ahead_ms) * 1'000'000;
    if (running && o.frame_loop) {
      XrFrameState fs{XR_TYPE_FRAME_STATE};
      CHECK(xrWaitFrame(session, nullptr, &fs));
      XrFrameBeginInfo fbi{XR_TYPE_FRAME_BEGIN_INFO};
      CHECK(xrBeginFrame(session, &fbi));
      XrFrameEndInfo fei{XR_TYPE_FRAME_END_INFO, nullptr, fs.predictedDisplayTime, XR_ENVIRONMENT_BLEND_MODE_OPAQUE, 0,
                         nullptr};
      CHECK(xrEndFrame(session, &fei));
      if (fs.predictedDisplayTime > 0) when = fs.predictedDisplayTime;
    }
    if (running && read_gaze(when) != 0) return 1;
    if (!o.frame_loop || !running) std::this_thread::sleep_for(std::chrono::milliseconds(o.interval_ms));
  }
  if (running) {
    // The orderly end: ask to exit, wait for STOPPING, then end the session.
    CHECK(xrRequestExitSession(session));
    for (int i = 0; i < 200 && state != XR_SESSION_STATE_STOPPING; ++i) {
      XrEventDataBuffer ev{XR_TYPE_EVENT_DATA_BUFFER};
      if (xrPollEvent(instance, &ev) == XR_SUCCESS && ev.type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED)
        state = reinterpret_cast<XrEventDataSessionStateChanged*>(&ev)->state;
      else
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    if (state == XR_SESSION_STATE_STOPPING) {
      if (read_gaze(xr_now()) != 0) return 1;  // no focus now: the gaze must be inactive
      CHECK(xrEndSession(session));
    }
  }
  if (tracker != XR_NULL_HANDLE) destroy_tracker(tracker);
  xrDestroySession(session);
  if (o.second_set) {
    // An app's next session with an action set of its own: its gaze binding is
    // suggested after the first set was attached, which the specification allows.
    std::strcpy(asci.actionSetName, "gaze_again");
    std::strcpy(asci.localizedActionSetName, "Gaze again");
    XrActionSet set2 = XR_NULL_HANDLE;
    CHECK(xrCreateActionSet(instance, &asci, &set2));
    XrAction action2 = XR_NULL_HANDLE;
    CHECK(xrCreateAction(set2, &aci, &action2));
    XrActionSuggestedBinding b2{action2, binding};
    XrInteractionProfileSuggestedBinding sb2{XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING, nullptr, profile, 1, &b2};
    std::printf("{\"event\":\"second_set\",\"suggest\":%d}\n", (int)xrSuggestInteractionProfileBindings(instance, &sb2));
  }
  const std::int64_t destroy_start = monotonic_ns();
  xrDestroyInstance(instance);
  std::printf("{\"event\":\"destroyed\",\"destroy_instance_ms\":%.3f}\n", (double)(monotonic_ns() - destroy_start) / 1e6);
  if (o.bench > 0) {  // asked for figures and has none: a failure, not a quiet success
    std::fprintf(stderr,
                 "openxr_gaze: --bench: the gaze never became active in %g s, nothing was timed. Is foveal's layer "
                 "where the loader looks (a build tree: XDG_DATA_DIRS=build/openxr/share) and foveald serving? "
                 "`foveal openxr` tells.\n",
                 o.duration_s);
    return 1;
  }
  return 0;
}

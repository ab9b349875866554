// A stand-in for the Khronos loader, for the openxr tests only (libopenxr_loader.so.1,
// put before the system's with LD_LIBRARY_PATH). Debian's loader (1.0.20) refuses
// apiVersion 1.1 itself, before any layer, so an OpenXR 1.1 instance on Monado (which
// takes 1.1) is reached through this instead. It does what the loader does for one
// layer over one runtime, and nothing more: negotiates with both, chains the layer over
// the runtime at xrCreateInstance, and sends the app's calls through the layer's
// xrGetInstanceProcAddr. No manifest search, no validation, one instance.
// Environment: XR_RUNTIME_JSON (the runtime's manifest), FOVEAL_TEST_LAYER_LIBRARY (the
// layer's library; unset or empty: the app talks to the runtime alone).
#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "loader_interface.h"

#define EXPORT extern "C" __attribute__((visibility("default"))) XRAPI_ATTR XrResult XRAPI_CALL

namespace {

// The runtime side of negotiation (the loader specification's runtime interface).
struct NegotiateRuntimeRequest {
  XrLoaderInterfaceStructs structType;
  uint32_t structVersion;
  size_t structSize;
  uint32_t runtimeInterfaceVersion;
  XrVersion runtimeApiVersion;
  PFN_xrGetInstanceProcAddr getInstanceProcAddr;
};
using NegotiateRuntime = XrResult(XRAPI_PTR*)(const XrNegotiateLoaderInfo*, NegotiateRuntimeRequest*);
using NegotiateLayer = XrResult(XRAPI_PTR*)(const XrNegotiateLoaderInfo*, const char*, XrNegotiateApiLayerRequest*);
constexpr const char* kLayerName = "XR_APILAYER_FOVEAL_gaze";

struct Chain {
  bool loaded = false;
  PFN_xrGetInstanceProcAddr runtime = nullptr;  // the runtime's xrGetInstanceProcAddr
  PFN_xrGetInstanceProcAddr layer = nullptr;    // the layer's, when one is loaded
  PFN_xrCreateApiLayerInstance layer_create = nullptr;
  PFN_xrGetInstanceProcAddr top = nullptr;      // what the app's calls go through
  XrInstance instance = XR_NULL_HANDLE;
} g;

void fail(const std::string& why) { std::fprintf(stderr, "direct_loader: %s\n", why.c_str()); }

XrNegotiateLoaderInfo loader_info() {
  return {XR_LOADER_INTERFACE_STRUCT_LOADER_INFO, XR_LOADER_INFO_STRUCT_VERSION, sizeof(XrNegotiateLoaderInfo), 1, 1,
          XR_MAKE_VERSION(1, 0, 0), XR_MAKE_VERSION(1, 0x3ff, 0xfff)};
}

bool load() {
  if (g.loaded) return g.runtime != nullptr;
  g.loaded = true;
  const char* manifest = std::getenv("XR_RUNTIME_JSON");
  if (!manifest) return fail("XR_RUNTIME_JSON is not set"), false;
  std::ifstream in(manifest);
  std::stringstream text;
  text << in.rdbuf();
  const auto j = nlohmann::json::parse(text.str(), nullptr, false);
  if (!j.is_object() || !j.contains("runtime") || !j["runtime"].value("library_path", "").size())
    return fail(std::string("no runtime.library_path in ") + manifest), false;
  std::filesystem::path lib = j["runtime"]["library_path"].get<std::string>();
  if (lib.is_relative()) lib = std::filesystem::path(manifest).parent_path() / lib;
  void* rt = ::dlopen(lib.c_str(), RTLD_NOW | RTLD_LOCAL);
  auto negotiate_rt = rt ? reinterpret_cast<NegotiateRuntime>(::dlsym(rt, "xrNegotiateLoaderRuntimeInterface")) : nullptr;
  if (!negotiate_rt) return fail("cannot load the runtime " + lib.string() + ": " + ::dlerror()), false;
  const XrNegotiateLoaderInfo info = loader_info();
  NegotiateRuntimeRequest rr{XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST, 1, sizeof(NegotiateRuntimeRequest), 0, 0, nullptr};
  if (XR_FAILED(negotiate_rt(&info, &rr)) || !rr.getInstanceProcAddr) return fail("the runtime refused to negotiate"), false;
  g.runtime = g.top = rr.getInstanceProcAddr;
  const char* layer_lib = std::getenv("FOVEAL_TEST_LAYER_LIBRARY");
  if (!layer_lib || !*layer_lib) return true;
  void* ly = ::dlopen(layer_lib, RTLD_NOW | RTLD_LOCAL);
  auto negotiate_ly = ly ? reinterpret_cast<NegotiateLayer>(::dlsym(ly, "xrNegotiateLoaderApiLayerInterface")) : nullptr;
  if (!negotiate_ly) return fail(std::string("cannot load the layer ") + layer_lib + ": " + ::dlerror()), g.runtime = nullptr, false;
  XrNegotiateApiLayerRequest lr{XR_LOADER_INTERFACE_STRUCT_API_LAYER_REQUEST, XR_API_LAYER_INFO_STRUCT_VERSION,
                                sizeof(XrNegotiateApiLayerRequest), 0, 0, nullptr, nullptr};
  if (XR_FAILED(negotiate_ly(&info, kLayerName, &lr)) || !lr.getInstanceProcAddr || !lr.createApiLayerInstance)
    return fail("the layer refused to negotiate"), g.runtime = nullptr, false;
  g.layer = lr.getInstanceProcAddr;
  g.layer_create = lr.createApiLayerInstance;
  return true;
}

// The end of the chain: the runtime's own xrCreateInstance (the loader's terminator).
XRAPI_ATTR XrResult XRAPI_CALL terminator(const XrInstanceCreateInfo* info, const XrApiLayerCreateInfo*,
                                          XrInstance* instance) {
  PFN_xrCreateInstance create = nullptr;
  if (XR_FAILED(g.runtime(XR_NULL_HANDLE, "xrCreateInstance", reinterpret_cast<PFN_xrVoidFunction*>(&create))))
    return XR_ERROR_INITIALIZATION_FAILED;
  return create(info, instance);
}

XrResult resolve(const char* name, PFN_xrVoidFunction* f) {
  if (!load()) return XR_ERROR_RUNTIME_UNAVAILABLE;
  return g.top(g.instance, name, f);
}

}  // namespace

EXPORT xrEnumerateInstanceExtensionProperties(const char* layer, uint32_t cap, uint32_t* count,
                                              XrExtensionProperties* props) {
  if (!load()) return XR_ERROR_RUNTIME_UNAVAILABLE;
  PFN_xrEnumerateInstanceExtensionProperties f = nullptr;
  g.runtime(XR_NULL_HANDLE, "xrEnumerateInstanceExtensionProperties", reinterpret_cast<PFN_xrVoidFunction*>(&f));
  return f ? f(layer, cap, count, props) : XR_ERROR_RUNTIME_FAILURE;
}

EXPORT xrEnumerateApiLayerProperties(uint32_t cap, uint32_t* count, XrApiLayerProperties* props) {
  if (!load()) return XR_ERROR_RUNTIME_UNAVAILABLE;
  *count = g.layer ? 1 : 0;
  if (cap == 0 || !g.layer) return XR_SUCCESS;
  std::snprintf(props[0].layerName, XR_MAX_API_LAYER_NAME_SIZE, "%s", kLayerName);
  return XR_SUCCESS;
}

EXPORT xrCreateInstance(const XrInstanceCreateInfo* info, XrInstance* instance) {
  if (!load()) return XR_ERROR_RUNTIME_UNAVAILABLE;
  if (!g.layer) {
    const XrResult r = terminator(info, nullptr, instance);
    if (XR_SUCCEEDED(r)) g.instance = *instance;
    return r;
  }
  XrApiLayerNextInfo next{XR_LOADER_INTERFACE_STRUCT_API_LAYER_NEXT_INFO, XR_API_LAYER_NEXT_INFO_STRUCT_VERSION,
                          sizeof(XrApiLayerNextInfo), {}, g.runtime, terminator, nullptr};
  std::snprintf(next.layerName, XR_MAX_API_LAYER_NAME_SIZE, "%s", kLayerName);
  XrApiLayerCreateInfo create{XR_LOADER_INTERFACE_STRUCT_API_LAYER_CREATE_INFO, XR_API_LAYER_CREATE_INFO_STRUCT_VERSION,
                              sizeof(XrApiLayerCreateInfo), nullptr, {}, &next};
  const XrResult r = g.layer_create(info, &create, instance);
  if (XR_SUCCEEDED(r)) g.instance = *instance, g.top = g.layer;
  return r;
}

EXPORT xrGetInstanceProcAddr(XrInstance instance, const char* name, PFN_xrVoidFunction* function) {
  if (!load()) return XR_ERROR_RUNTIME_UNAVAILABLE;
  return g.top(instance, name, function);
}

// Every other call the app links to, through the chain's xrGetInstanceProcAddr.
#define FORWARD(name, params, args)                                                                \
  EXPORT name params {                                                                             \
    PFN_##name f = nullptr;                                                                        \
    if (XR_FAILED(resolve(#name, reinterpret_cast<PFN_xrVoidFunction*>(&f))) || !f) return XR_ERROR_FUNCTION_UNSUPPORTED; \
    return f args;                                                                                 \
  }

FORWARD(xrDestroyInstance, (XrInstance i), (i))
FORWARD(xrResultToString, (XrInstance i, XrResult r, char s[XR_MAX_RESULT_STRING_SIZE]), (i, r, s))
FORWARD(xrGetInstanceProperties, (XrInstance i, XrInstanceProperties* p), (i, p))
FORWARD(xrGetSystem, (XrInstance i, const XrSystemGetInfo* g_, XrSystemId* s), (i, g_, s))
FORWARD(xrGetSystemProperties, (XrInstance i, XrSystemId s, XrSystemProperties* p), (i, s, p))
FORWARD(xrEnumerateViewConfigurations,
        (XrInstance i, XrSystemId s, uint32_t c, uint32_t* n, XrViewConfigurationType* t), (i, s, c, n, t))
FORWARD(xrCreateActionSet, (XrInstance i, const XrActionSetCreateInfo* c, XrActionSet* s), (i, c, s))
FORWARD(xrCreateAction, (XrActionSet s, const XrActionCreateInfo* c, XrAction* a), (s, c, a))
FORWARD(xrStringToPath, (XrInstance i, const char* s, XrPath* p), (i, s, p))
FORWARD(xrSuggestInteractionProfileBindings, (XrInstance i, const XrInteractionProfileSuggestedBinding* b), (i, b))
FORWARD(xrCreateSession, (XrInstance i, const XrSessionCreateInfo* c, XrSession* s), (i, c, s))
FORWARD(xrDestroySession, (XrSession s), (s))
FORWARD(xrAttachSessionActionSets, (XrSession s, const XrSessionActionSetsAttachInfo* a), (s, a))
FORWARD(xrCreateActionSpace, (XrSession s, const XrActionSpaceCreateInfo* c, XrSpace* p), (s, c, p))
FORWARD(xrCreateReferenceSpace, (XrSession s, const XrReferenceSpaceCreateInfo* c, XrSpace* p), (s, c, p))
FORWARD(xrSyncActions, (XrSession s, const XrActionsSyncInfo* i), (s, i))
FORWARD(xrGetActionStatePose, (XrSession s, const XrActionStateGetInfo* i, XrActionStatePose* p), (s, i, p))
FORWARD(xrLocateSpace, (XrSpace s, XrSpace b, XrTime t, XrSpaceLocation* l), (s, b, t, l))
FORWARD(xrPollEvent, (XrInstance i, XrEventDataBuffer* e), (i, e))
FORWARD(xrBeginSession, (XrSession s, const XrSessionBeginInfo* b), (s, b))
FORWARD(xrEndSession, (XrSession s), (s))
FORWARD(xrRequestExitSession, (XrSession s), (s))
FORWARD(xrWaitFrame, (XrSession s, const XrFrameWaitInfo* w, XrFrameState* f_), (s, w, f_))
FORWARD(xrBeginFrame, (XrSession s, const XrFrameBeginInfo* b), (s, b))
FORWARD(xrEndFrame, (XrSession s, const XrFrameEndInfo* e), (s, e))

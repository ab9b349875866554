// XR_VARJO_quad_views (and the OpenXR 1.1 inset configuration of the same value) on a
// runtime that has only stereo: the layer answers the view configuration calls with
// four views (0/1 outer, 2/3 inner), places the inner views on foveald's gaze in
// xrLocateViews, and composes them into stereo at xrEndFrame (frame_composition.cpp).
// docs/openxr.md, "Quad views".
#include <dlfcn.h>

#include <cmath>
#include <cstdlib>
#include <cstring>

#include "inset_quality.hpp"
#include "pose_math.hpp"
#include "quad_session.hpp"

namespace foveal::openxr {

namespace {

constexpr XrViewConfigurationType kQuad = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_QUAD_VARJO;
constexpr XrViewConfigurationType kStereo = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;

bool serving() { return layer().quad_views(); }

QuadSession* quad_of(XrSession s) {
  SessionSlot* slot = find_session(s);
  return slot ? slot->quad.get() : nullptr;
}

/// The first struct of `type` in a chain, or null.
const XrBaseInStructure* find_in(const void* chain, XrStructureType type) {
  for (auto* p = static_cast<const XrBaseInStructure*>(chain); p; p = p->next)
    if (p->type == type) return p;
  return nullptr;
}

// The app's GL entry points: EGL's loader from the binding, or GLX's from the process.
PFNEGLGETPROCADDRESSPROC g_egl_get_proc = nullptr;
void* egl_get_proc(const char* name) { return reinterpret_cast<void*>(g_egl_get_proc(name)); }
using GlxGetProc = void* (*)(const unsigned char*);
GlxGetProc g_glx_get_proc = nullptr;
void* glx_get_proc(const char* name) { return g_glx_get_proc(reinterpret_cast<const unsigned char*>(name)); }

#ifdef FOVEAL_OPENXR_VULKAN
/// The app's Vulkan loader: vkGetInstanceProcAddr as the process has it, or from the
/// libvulkan it loaded (the handles it gave us are that loader's). Kept open.
PFN_vkGetInstanceProcAddr app_vulkan_loader() {
  if (void* f = ::dlsym(RTLD_DEFAULT, "vkGetInstanceProcAddr")) return reinterpret_cast<PFN_vkGetInstanceProcAddr>(f);
  void* lib = ::dlopen("libvulkan.so.1", RTLD_NOW | RTLD_NOLOAD);
  if (!lib) lib = ::dlopen("libvulkan.so.1", RTLD_NOW);
  return lib ? reinterpret_cast<PFN_vkGetInstanceProcAddr>(::dlsym(lib, "vkGetInstanceProcAddr")) : nullptr;
}
#endif

const InsetSettings& settings_once() {
  static const InsetSettings s = [] {
    const char* problem = nullptr;
    InsetSettings v = inset_settings_from_environment(&problem);
    if (problem) log_line(problem);
    return v;
  }();
  return s;
}

// FOVEAL_OPENXR_QUALITY's table, loaded once (at the first size or session, never in a frame).
const InsetQuality& quality_once() {
  static const InsetQuality q = [] {
    InsetQuality v = InsetQuality::from_environment();
    if (!v.problem().empty()) log_line(v.problem().c_str());
    return v;
  }();
  return q;
}

// The inset's settings and the outer views' densities (0 left, 1 right): the quality's
// choice from its table where it is on, else FOVEAL_OPENXR_INSET and 1/σ of foveald's pair.
InsetSettings sized_inset(const GazeSettings& gs, float density[2]) {
  InsetSettings s = settings_once();
  density[0] = 1.0f / gs.sigma[0], density[1] = 1.0f / gs.sigma[1];
  quality_once().apply(gs.sigma, s, density);
  return s;
}

}  // namespace

bool gaze_tangent_in_view(const XrPosef& view_pose, const XrPosef& head_pose, const XrVector3f& gaze_in_head, float& tx,
                          float& ty) {
  // The gaze leaves the head; the view may be turned against it (canted displays).
  const XrQuaternionf to_view = quat_mul(inverse(view_pose).orientation, head_pose.orientation);
  const XrVector3f d = rotate(to_view, gaze_in_head);
  if (!(d.z < -0.05f)) return false;  // at or behind the view's side: no point on its plane
  tx = d.x / -d.z;
  ty = d.y / -d.z;
  return std::isfinite(tx) && std::isfinite(ty);
}

void QuadSessionDeleter::operator()(QuadSession* q) const { delete q; }

void quad_session_created(SessionSlot& slot, const XrSessionCreateInfo* info) {
  slot.quad.reset();
  Layer& l = layer();
  if (!l.quad_views()) return;
  std::unique_ptr<QuadSession, QuadSessionDeleter> q(new QuadSession);
  q->session = XR_NULL_HANDLE;
  if (const auto* egl = reinterpret_cast<const XrGraphicsBindingEGLMNDX*>(find_in(info->next, XR_TYPE_GRAPHICS_BINDING_EGL_MNDX))) {
    q->api = QuadSession::Api::opengl;
    g_egl_get_proc = egl->getProcAddress;
    q->get_proc = egl->getProcAddress ? egl_get_proc : nullptr;
  } else if (find_in(info->next, XR_TYPE_GRAPHICS_BINDING_OPENGL_XLIB_KHR) ||
             find_in(info->next, XR_TYPE_GRAPHICS_BINDING_OPENGL_XCB_KHR) ||
             find_in(info->next, XR_TYPE_GRAPHICS_BINDING_OPENGL_WAYLAND_KHR)) {
    q->api = QuadSession::Api::opengl;
    g_glx_get_proc = reinterpret_cast<GlxGetProc>(::dlsym(RTLD_DEFAULT, "glXGetProcAddressARB"));
    if (g_glx_get_proc) {
      q->get_proc = glx_get_proc;
    } else if (auto egl_get = reinterpret_cast<PFNEGLGETPROCADDRESSPROC>(::dlsym(RTLD_DEFAULT, "eglGetProcAddress"))) {
      g_egl_get_proc = egl_get;
      q->get_proc = egl_get_proc;
    }
  } else if (const auto* vk = find_in(info->next, XR_TYPE_GRAPHICS_BINDING_VULKAN_KHR)) {
    q->api = QuadSession::Api::vulkan;  // XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR is the same value and struct
#ifdef FOVEAL_OPENXR_VULKAN
    const auto* b = reinterpret_cast<const XrGraphicsBindingVulkanKHR*>(vk);
    q->vk = {app_vulkan_loader(), b->instance, b->physicalDevice, b->device, b->queueFamilyIndex, b->queueIndex};
#else
    (void)vk;
#endif
  }
  XrViewConfigurationView views[2] = {{XR_TYPE_VIEW_CONFIGURATION_VIEW, nullptr, 0, 0, 0, 0, 0, 0},
                                      {XR_TYPE_VIEW_CONFIGURATION_VIEW, nullptr, 0, 0, 0, 0, 0, 0}};
  std::uint32_t n = 0;
  if (XR_FAILED(l.next.EnumerateViewConfigurationViews(l.instance, info->systemId, kStereo, 2, &n, views)) || n != 2) {
    log_line("the runtime has no stereo view configuration: no quad views in this session");
    return;
  }
  for (int e = 0; e < 2; ++e) {
    q->stereo_w[e] = views[e].recommendedImageRectWidth;
    q->stereo_h[e] = views[e].recommendedImageRectHeight;
  }
  float densities[2];
  q->inset = sized_inset(l.feed ? l.feed->settings() : GazeSettings{}, densities);
  if (const char* dir = std::getenv("FOVEAL_OPENXR_CAPTURE_DIR"); dir && *dir) {
    q->capture_dir = dir;
    const char* frame = std::getenv("FOVEAL_OPENXR_CAPTURE_FRAME");
    q->capture_frame = frame && *frame ? std::strtol(frame, nullptr, 10) : 0;
  }
  slot.quad = std::move(q);
}

void quad_session_destroyed(SessionSlot& slot) {
  if (!slot.quad) return;
  QuadSession& q = *slot.quad;
  q.composer.reset();  // first: a Vulkan composer waits for its work on the images before they go
  for (auto& o : q.out)
    if (o.handle != XR_NULL_HANDLE) layer().next.DestroySwapchain(o.handle);
  slot.quad.reset();  // the composer's GL objects go with the app's context, which is current here or gone
}

SwapchainRecord* find_swapchain(XrSwapchain s, QuadSession** session) {
  if (s == XR_NULL_HANDLE) return nullptr;
  for (auto& slot : layer().sessions) {
    if (slot.handle.load(std::memory_order_acquire) == XR_NULL_HANDLE || !slot.quad) continue;
    if (SwapchainRecord* r = find_slot(slot.quad->swapchains, s)) {
      if (session) *session = slot.quad.get();
      return r;
    }
  }
  return nullptr;
}

namespace {

XRAPI_ATTR XrResult XRAPI_CALL layer_xrEnumerateViewConfigurations(XrInstance instance, XrSystemId system,
                                                                   std::uint32_t capacity, std::uint32_t* count,
                                                                   XrViewConfigurationType* types) {
  Layer& l = layer();
  if (!serving() || !count) return l.next.EnumerateViewConfigurations(instance, system, capacity, count, types);
  XrViewConfigurationType own[16];
  std::uint32_t n = 0;
  XrResult r = l.next.EnumerateViewConfigurations(instance, system, 16, &n, own);
  if (XR_FAILED(r)) return r;
  bool stereo = false, quad = false;
  for (std::uint32_t i = 0; i < n; ++i) stereo |= own[i] == kStereo, quad |= own[i] == kQuad;
  // After stereo: an app that takes the first it knows keeps getting stereo.
  if (stereo && !quad && n < 16) {
    std::uint32_t at = 0;
    while (own[at] != kStereo) ++at;
    for (std::uint32_t i = n; i > at + 1; --i) own[i] = own[i - 1];
    own[at + 1] = kQuad;
    ++n;
  }
  *count = n;
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < n || !types) return XR_ERROR_SIZE_INSUFFICIENT;
  for (std::uint32_t i = 0; i < n; ++i) types[i] = own[i];
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrGetViewConfigurationProperties(XrInstance instance, XrSystemId system,
                                                                      XrViewConfigurationType type,
                                                                      XrViewConfigurationProperties* props) {
  Layer& l = layer();
  if (!serving() || type != kQuad) return l.next.GetViewConfigurationProperties(instance, system, type, props);
  const XrResult r = l.next.GetViewConfigurationProperties(instance, system, kStereo, props);
  if (XR_SUCCEEDED(r)) props->viewConfigurationType = kQuad;
  return r;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrEnumerateViewConfigurationViews(XrInstance instance, XrSystemId system,
                                                                       XrViewConfigurationType type,
                                                                       std::uint32_t capacity, std::uint32_t* count,
                                                                       XrViewConfigurationView* views) {
  Layer& l = layer();
  if (!serving() || type != kQuad)
    return l.next.EnumerateViewConfigurationViews(instance, system, type, capacity, count, views);
  if (!count) return XR_ERROR_VALIDATION_FAILURE;
  *count = 4;
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < 4 || !views) return XR_ERROR_SIZE_INSUFFICIENT;
  XrViewConfigurationView stereo[2] = {{XR_TYPE_VIEW_CONFIGURATION_VIEW, nullptr, 0, 0, 0, 0, 0, 0},
                                       {XR_TYPE_VIEW_CONFIGURATION_VIEW, nullptr, 0, 0, 0, 0, 0, 0}};
  std::uint32_t n = 0;
  const XrResult r = l.next.EnumerateViewConfigurationViews(instance, system, kStereo, 2, &n, stereo);
  if (XR_FAILED(r)) return r;
  if (n != 2) return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
  // XrFoveatedViewConfigurationViewVARJO asks for the sizes with foveation on.
  bool foveated = false;
  if (l.foveated_rendering())
    if (auto* f = reinterpret_cast<const XrFoveatedViewConfigurationViewVARJO*>(
            find_in(views[0].next, XR_TYPE_FOVEATED_VIEW_CONFIGURATION_VIEW_VARJO)))
      foveated = f->foveatedRenderingActive;
  const GazeSettings gs = l.feed ? l.feed->settings() : GazeSettings{};
  float density[2];
  const InsetSettings inset = sized_inset(gs, density);
  const std::uint32_t w[2] = {stereo[0].recommendedImageRectWidth, stereo[1].recommendedImageRectWidth};
  const std::uint32_t h[2] = {stereo[0].recommendedImageRectHeight, stereo[1].recommendedImageRectHeight};
  const QuadSizes sizes = quad_sizes(w, h, density, foveated ? inset.foveated_share_x : inset.fixed_share_x,
                                     foveated ? inset.foveated_share_y : inset.fixed_share_y);
  for (int i = 0; i < 4; ++i) {
    const XrViewConfigurationView& s = stereo[i % 2];
    views[i].recommendedImageRectWidth = sizes.width[i];
    views[i].recommendedImageRectHeight = sizes.height[i];
    views[i].maxImageRectWidth = s.maxImageRectWidth;
    views[i].maxImageRectHeight = s.maxImageRectHeight;
    views[i].recommendedSwapchainSampleCount = s.recommendedSwapchainSampleCount;
    views[i].maxSwapchainSampleCount = s.maxSwapchainSampleCount;
  }
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrBeginSession(XrSession session, const XrSessionBeginInfo* info) {
  Layer& l = layer();
  if (!serving() || !info || info->primaryViewConfigurationType != kQuad) return l.next.BeginSession(session, info);
  QuadSession* q = quad_of(session);
  if (!q) return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
#ifdef FOVEAL_OPENXR_VULKAN
  const bool composable = q->api == QuadSession::Api::opengl || q->api == QuadSession::Api::vulkan;
#else
  const bool composable = q->api == QuadSession::Api::opengl;
#endif
  if (!composable) {
    log_line("quad views: the layer composes them on OpenGL and Vulkan sessions (Vulkan where it was built with "
             "libvulkan-dev and glslang-tools); this session's graphics API is not one");
    return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
  }
  XrSessionBeginInfo down = *info;
  down.primaryViewConfigurationType = kStereo;
  const XrResult r = l.next.BeginSession(session, &down);
  if (XR_SUCCEEDED(r)) {
    q->session = session;
    q->began_quad.store(true, std::memory_order_release);
  }
  return r;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrLocateViews(XrSession session, const XrViewLocateInfo* info, XrViewState* state,
                                                   std::uint32_t capacity, std::uint32_t* count, XrView* views) {
  Layer& l = layer();
  if (!serving() || !info || info->viewConfigurationType != kQuad)
    return l.next.LocateViews(session, info, state, capacity, count, views);
  SessionSlot* slot = find_session(session);
  QuadSession* q = slot ? slot->quad.get() : nullptr;
  if (!q) return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
  if (!count || !state) return XR_ERROR_VALIDATION_FAILURE;
  *count = 4;
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < 4 || !views) return XR_ERROR_SIZE_INSUFFICIENT;

  // The runtime sees a stereo locate without the foveation struct it does not know.
  const XrBaseInStructure* fov_struct = find_in(info->next, XR_TYPE_VIEW_LOCATE_FOVEATED_RENDERING_VARJO);
  const bool foveated =
      l.foveated_rendering() && fov_struct &&
      reinterpret_cast<const XrViewLocateFoveatedRenderingVARJO*>(fov_struct)->foveatedRenderingActive;
  XrViewLocateInfo down = *info;
  down.viewConfigurationType = kStereo;
  XrBaseInStructure* patched = nullptr;
  if (fov_struct) {
    if (down.next == fov_struct) {
      down.next = fov_struct->next;
    } else {
      for (auto* p = const_cast<XrBaseInStructure*>(static_cast<const XrBaseInStructure*>(down.next)); p; p = const_cast<XrBaseInStructure*>(p->next))
        if (p->next == fov_struct) {
          patched = p;
          p->next = fov_struct->next;
          break;
        }
    }
  }
  XrView stereo[2] = {{XR_TYPE_VIEW, nullptr, identity_pose(), {}}, {XR_TYPE_VIEW, nullptr, identity_pose(), {}}};
  std::uint32_t n = 0;
  const XrResult r = l.next.LocateViews(session, &down, state, 2, &n, stereo);
  if (patched) patched->next = fov_struct;
  if (XR_FAILED(r)) return r;
  if (n != 2) return XR_ERROR_RUNTIME_FAILURE;

  // An app that reads the gaze itself gets its inner views on the very sample its action
  // state latched at xrSyncActions (a gaze cursor sits in the inset's centre); any other
  // app on the newest sample. Either is predicted to displayTime, as the app's own locate
  // of the gaze at that time is.
  GazeNow g;
  XrSpaceLocation head{};
  const bool read = slot->app_reads_gaze.load(std::memory_order_acquire) ? slot->latched.load(g)
                                                                         : l.feed && l.feed->read(g);
  if (read) g = gaze_at(g, info->displayTime);  // that sample, predicted to when the frame is shown
  const bool have_gaze = foveated && read && g.tracked &&
                         XR_SUCCEEDED(locate_head(*slot, info->space, info->displayTime, head)) &&
                         (head.locationFlags & XR_SPACE_LOCATION_ORIENTATION_VALID_BIT);
  for (int e = 0; e < 2; ++e) {
    views[e].pose = views[e + 2].pose = stereo[e].pose;  // views 0/2 and 1/3: one pose
    views[e].fov = stereo[e].fov;
    const TanRect outer = to_tangents(stereo[e].fov);
    float tx = 0, ty = 0;
    const bool valid = have_gaze && gaze_tangent_in_view(stereo[e].pose, head.pose,
                                                         g.eye_tracked[e] ? g.eye_dir[e] : g.combined, tx, ty);
    views[e + 2].fov = to_fov(q->motion[e].update(outer, q->inset, valid, tx, ty, info->displayTime));
  }
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrEndFrame(XrSession session, const XrFrameEndInfo* info) {
  Layer& l = layer();
  QuadSession* q = serving() ? quad_of(session) : nullptr;
  if (!q || !q->began_quad.load(std::memory_order_acquire)) return l.next.EndFrame(session, info);
  return end_quad_frame(*q, info);
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrCreateSwapchain(XrSession session, const XrSwapchainCreateInfo* info,
                                                       XrSwapchain* swapchain) {
  Layer& l = layer();
  QuadSession* q = serving() ? quad_of(session) : nullptr;
  if (!q || !info || !swapchain) return l.next.CreateSwapchain(session, info, swapchain);
  // The composer samples the app's images.
  XrSwapchainCreateInfo down = *info;
  if (down.usageFlags & XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT) down.usageFlags |= XR_SWAPCHAIN_USAGE_SAMPLED_BIT;
  const XrResult r = l.next.CreateSwapchain(session, &down, swapchain);
  if (XR_FAILED(r)) return r;
  std::lock_guard lock(l.mutex);
  const bool claimed = claim_slot(q->swapchains, *swapchain, [&](SwapchainRecord& s) {
    s.format = info->format;
    s.width = info->width;
    s.height = info->height;
    s.array_size = info->arraySize;
    s.image_count = 0;
    s.acquired_head = s.acquired_count = 0;
    s.released = -1;
    s.serial = next_swapchain_serial();
  });
  if (!claimed) log_line("more than 32 swapchains in a session: the later ones cannot be composed");
  return r;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrDestroySwapchain(XrSwapchain swapchain) {
  Layer& l = layer();
  if (SwapchainRecord* s = find_swapchain(swapchain)) forward_release(*s);  // a release held for xrEndFrame goes first
  {
    std::lock_guard lock(l.mutex);
    if (SwapchainRecord* s = find_swapchain(swapchain)) s->handle.store(XR_NULL_HANDLE);
  }
  return l.next.DestroySwapchain(swapchain);
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrEnumerateSwapchainImages(XrSwapchain swapchain, std::uint32_t capacity,
                                                                std::uint32_t* count, XrSwapchainImageBaseHeader* images) {
  const XrResult r = layer().next.EnumerateSwapchainImages(swapchain, capacity, count, images);
  SwapchainRecord* s = XR_SUCCEEDED(r) && capacity > 0 && images ? find_swapchain(swapchain) : nullptr;
  if (s && images->type == XR_TYPE_SWAPCHAIN_IMAGE_OPENGL_KHR) {
    const auto* gl = reinterpret_cast<const XrSwapchainImageOpenGLKHR*>(images);
    s->image_count = std::min<std::uint32_t>(*count, 8);
    for (std::uint32_t i = 0; i < s->image_count; ++i) s->images[i] = gl[i].image;
  }
#ifdef FOVEAL_OPENXR_VULKAN
  if (s && images->type == XR_TYPE_SWAPCHAIN_IMAGE_VULKAN_KHR) {
    const auto* vk = reinterpret_cast<const XrSwapchainImageVulkanKHR*>(images);
    s->image_count = std::min<std::uint32_t>(*count, 8);
    for (std::uint32_t i = 0; i < s->image_count; ++i) s->images[i] = reinterpret_cast<std::uint64_t>(vk[i].image);
  }
#endif
  return r;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrAcquireSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageAcquireInfo* info,
                                                             std::uint32_t* index) {
  if (SwapchainRecord* held = find_swapchain(swapchain)) forward_release(*held);  // the runtime's order of calls
  const XrResult r = layer().next.AcquireSwapchainImage(swapchain, info, index);
  SwapchainRecord* s = XR_SUCCEEDED(r) && index ? find_swapchain(swapchain) : nullptr;
  if (s && s->acquired_count < 8) {
    s->acquired[(s->acquired_head + s->acquired_count) % 8] = static_cast<int>(*index);
    ++s->acquired_count;
  }
  return r;
}

XRAPI_ATTR XrResult XRAPI_CALL layer_xrReleaseSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageReleaseInfo* info) {
  QuadSession* q = nullptr;
  SwapchainRecord* held = find_swapchain(swapchain, &q);
  const bool hold = holds_release(q, held);  // Vulkan: released at xrEndFrame, after the layer samples it
  const XrResult r = hold ? XR_SUCCESS : layer().next.ReleaseSwapchainImage(swapchain, info);
  if (hold) held->release_held.store(true, std::memory_order_release);
  SwapchainRecord* s = XR_SUCCEEDED(r) ? held : nullptr;
  if (s && s->acquired_count > 0) {  // released in the order acquired
    s->released.store(s->acquired[s->acquired_head], std::memory_order_release);
    s->acquired_head = (s->acquired_head + 1) % 8;
    --s->acquired_count;
  }
  return r;
}

const Intercept kFunctions[] = {
    {"xrEnumerateViewConfigurations", FOVEAL_FN(layer_xrEnumerateViewConfigurations), false},
    {"xrGetViewConfigurationProperties", FOVEAL_FN(layer_xrGetViewConfigurationProperties), false},
    {"xrEnumerateViewConfigurationViews", FOVEAL_FN(layer_xrEnumerateViewConfigurationViews), false},
    {"xrBeginSession", FOVEAL_FN(layer_xrBeginSession), false},
    {"xrLocateViews", FOVEAL_FN(layer_xrLocateViews), false},
    {"xrEndFrame", FOVEAL_FN(layer_xrEndFrame), false},
    {"xrCreateSwapchain", FOVEAL_FN(layer_xrCreateSwapchain), false},
    {"xrDestroySwapchain", FOVEAL_FN(layer_xrDestroySwapchain), false},
    {"xrEnumerateSwapchainImages", FOVEAL_FN(layer_xrEnumerateSwapchainImages), false},
    {"xrAcquireSwapchainImage", FOVEAL_FN(layer_xrAcquireSwapchainImage), false},
    {"xrReleaseSwapchainImage", FOVEAL_FN(layer_xrReleaseSwapchainImage), false},
};

}  // namespace

const ServedExtension kVarjoQuadViews = {XR_VARJO_QUAD_VIEWS_EXTENSION_NAME, 1, kFunctions, std::size(kFunctions), {},
                                         nullptr, -1};

}  // namespace foveal::openxr

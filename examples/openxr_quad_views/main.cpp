// openxr_quad_views: an OpenXR application that renders a glTF scene into quad views
// (XR_VARJO_quad_views, with XR_VARJO_foveated_rendering when offered) or stereo,
// headless through EGL (XR_MNDX_egl_enable), and prints what it was given as JSON lines.
// It knows nothing of foveal: with foveal's layer on a stereo-only runtime, the quad
// views and their gaze-following inner fields are the layer's (docs/openxr.md).
//
//   openxr_quad_views [--scene GLTF] [--frames N] [--stereo] [--no-foveated]
//                     [--still] [--gaze] [--array] [--save-dir DIR --save-frame K] [--help]
//
// Lines: {"event":"system",...} (view configurations, supportsFoveatedRendering),
// {"event":"views",...} (the configuration used and each view's recommended size), then
// one {"event":"frame",...} per frame (display time and the time xrLocateViews was
// called, as CLOCK_MONOTONIC ns; each view's
// field of view as angles left,right,up,down, pose, image size) and {"event":"end"}.
// --gaze: the app reads the eye gaze too (XR_EXT_eye_gaze_interaction), syncing its
// actions before each xrLocateViews; each frame line then holds "gaze" (active, tracked,
// the sample's time as CLOCK_MONOTONIC ns).
// --save-dir: the app's own images of frame K, one PNG per view (view_<i>.png).
// --still: each view drawn from a head that stands still at the scene's viewer (only
// the eyes' offset and the fields of view from the runtime), so images repeat exactly.
// --array: every view in one swapchain of arraySize = the view count (GL_TEXTURE_2D_ARRAY),
// view i drawn into layer i at the layer's origin (imageArrayIndex i), as Unreal and
// Godot's multiview do.
#include <EGL/egl.h>
#include <time.h>
#define XR_USE_PLATFORM_EGL
#define XR_USE_GRAPHICS_API_OPENGL
#define XR_USE_TIMESPEC
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "foveal/image/image.hpp"
#include "foveal/render/egl_context.hpp"
#include "foveal/render/gl.hpp"
#include "gaze_reader.hpp"
#include "scene_renderer.hpp"

namespace {

struct Options {
  std::string scene = FOVEAL_EXAMPLE_DUNGEON;
  int frames = 60;
  bool stereo = false, foveated = true;
  bool still = false;  ///< render as if the head stood still at the origin (reproducible images)
  bool gaze = false;   ///< read the eye gaze through the action system each frame
  bool array = false;  ///< all views in layers of one array swapchain
  std::string save_dir;
  int save_frame = -1;
};

int usage(int rc) {
  std::fprintf(rc ? stderr : stdout,
               "usage: openxr_quad_views [--scene GLTF] [--frames N] [--stereo] [--no-foveated]\n"
               "                         [--still] [--gaze] [--array] [--save-dir DIR --save-frame K]\n"
               "  Renders a glTF scene (default: the bundled Dungeon) into OpenXR quad views (stereo with\n"
               "  --stereo) through EGL, headless, and prints JSON lines: what the runtime offered, the\n"
               "  views' sizes, each frame's views. --no-foveated: quad views without gaze.\n"
               "  --save-dir DIR --save-frame K: frame K's images as DIR/view_<i>.png.\n"
               "  --still: draw from a head that stands still (the runtime's fields of view, the eyes'\n"
               "  offsets), so the images of every run are the same.\n"
               "  --gaze: also read the eye gaze (XR_EXT_eye_gaze_interaction) each frame and print it.\n"
               "  --array: all views in one array swapchain (arraySize = the view count, each layer the\n"
               "  largest view's size), view i drawn into layer i (imageArrayIndex i) at its origin.\n");
  return rc;
}

XrInstance g_instance = XR_NULL_HANDLE;

#define CHECK(call)                                                                     \
  do {                                                                                  \
    const XrResult r_ = (call);                                                         \
    if (XR_FAILED(r_)) {                                                                \
      char name_[XR_MAX_RESULT_STRING_SIZE] = "?";                                      \
      if (g_instance != XR_NULL_HANDLE) xrResultToString(g_instance, r_, name_);        \
      std::fprintf(stderr, "openxr_quad_views: %s failed: %s (%d)\n", #call, name_, (int)r_); \
      return 1;                                                                         \
    }                                                                                   \
  } while (0)

template <typename F>
F proc(const char* name) {
  PFN_xrVoidFunction f = nullptr;
  xrGetInstanceProcAddr(g_instance, name, &f);
  return reinterpret_cast<F>(f);
}

bool has_extension(const char* name) {
  std::uint32_t n = 0;
  xrEnumerateInstanceExtensionProperties(nullptr, 0, &n, nullptr);
  std::vector<XrExtensionProperties> props(n, {XR_TYPE_EXTENSION_PROPERTIES});
  xrEnumerateInstanceExtensionProperties(nullptr, n, &n, props.data());
  for (const auto& p : props)
    if (std::strcmp(p.extensionName, name) == 0) return true;
  return false;
}

std::int64_t mono_of(XrTime t) {
  static auto to_timespec = proc<PFN_xrConvertTimeToTimespecTimeKHR>("xrConvertTimeToTimespecTimeKHR");
  timespec ts{};
  if (!to_timespec || XR_FAILED(to_timespec(g_instance, t, &ts))) return 0;
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

struct ViewTarget {
  XrSwapchain swapchain = XR_NULL_HANDLE;
  std::vector<XrSwapchainImageOpenGLKHR> images;
  int width = 0, height = 0;
};

/// The view's w×h pixels at the origin of `texture` (of its layer `layer`, an array's).
bool save_view(unsigned texture, int layer, int w, int h, const std::string& path) {
  foveal::image::Image img(w, h);
  std::vector<std::uint8_t> bottom_up(img.rgba.size());
  glGetTextureSubImage(texture, 0, 0, 0, layer, w, h, 1, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(bottom_up.size()),
                       bottom_up.data());
  const std::size_t row = static_cast<std::size_t>(w) * 4;
  for (int y = 0; y < h; ++y)
    std::memcpy(img.rgba.data() + static_cast<std::size_t>(y) * row, bottom_up.data() + static_cast<std::size_t>(h - 1 - y) * row, row);
  return static_cast<bool>(foveal::image::save_png(path, img));
}

int run(const Options& o) {
  auto egl = foveal::gl::EglContext::create();
  if (!egl) {
    std::fprintf(stderr, "openxr_quad_views: %s\n", egl.error().message.c_str());
    return 1;
  }
  auto renderer = example::SceneRenderer::create(o.scene);
  if (!renderer) {
    std::fprintf(stderr, "openxr_quad_views: %s\n", renderer.error().message.c_str());
    return 2;
  }
  const bool quad_ext = has_extension(XR_VARJO_QUAD_VIEWS_EXTENSION_NAME);
  const bool fov_ext = quad_ext && has_extension(XR_VARJO_FOVEATED_RENDERING_EXTENSION_NAME);
  std::vector<const char*> exts = {XR_MNDX_EGL_ENABLE_EXTENSION_NAME, XR_KHR_OPENGL_ENABLE_EXTENSION_NAME,
                                   XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME};
  if (quad_ext) exts.push_back(XR_VARJO_QUAD_VIEWS_EXTENSION_NAME);
  if (fov_ext) exts.push_back(XR_VARJO_FOVEATED_RENDERING_EXTENSION_NAME);
  if (o.gaze && !has_extension(XR_EXT_EYE_GAZE_INTERACTION_EXTENSION_NAME)) {
    std::fprintf(stderr, "openxr_quad_views: --gaze: no runtime or layer offers %s\n", XR_EXT_EYE_GAZE_INTERACTION_EXTENSION_NAME);
    return 1;
  }
  if (o.gaze) exts.push_back(XR_EXT_EYE_GAZE_INTERACTION_EXTENSION_NAME);
  XrInstanceCreateInfo ci{XR_TYPE_INSTANCE_CREATE_INFO};
  std::strcpy(ci.applicationInfo.applicationName, "openxr_quad_views");
  ci.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
  ci.enabledExtensionCount = static_cast<std::uint32_t>(exts.size());
  ci.enabledExtensionNames = exts.data();
  CHECK(xrCreateInstance(&ci, &g_instance));
  XrSystemGetInfo sgi{XR_TYPE_SYSTEM_GET_INFO};
  sgi.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
  XrSystemId system = XR_NULL_SYSTEM_ID;
  CHECK(xrGetSystem(g_instance, &sgi, &system));
  XrSystemFoveatedRenderingPropertiesVARJO fr{XR_TYPE_SYSTEM_FOVEATED_RENDERING_PROPERTIES_VARJO};
  XrSystemProperties sp{XR_TYPE_SYSTEM_PROPERTIES, fov_ext ? &fr : nullptr};
  CHECK(xrGetSystemProperties(g_instance, system, &sp));
  std::uint32_t nc = 0;
  CHECK(xrEnumerateViewConfigurations(g_instance, system, 0, &nc, nullptr));
  std::vector<XrViewConfigurationType> configs(nc);
  CHECK(xrEnumerateViewConfigurations(g_instance, system, nc, &nc, configs.data()));
  bool has_quad = false;
  std::string list;
  for (auto c : configs) {
    has_quad |= c == XR_VIEW_CONFIGURATION_TYPE_PRIMARY_QUAD_VARJO;
    list += (list.empty() ? "" : ",") + std::to_string(static_cast<int>(c));
  }
  std::printf("{\"event\":\"system\",\"quad_views_extension\":%s,\"foveated_rendering_extension\":%s,"
              "\"view_configurations\":[%s],\"supportsFoveatedRendering\":%d}\n",
              quad_ext ? "true" : "false", fov_ext ? "true" : "false", list.c_str(), fov_ext ? (int)fr.supportsFoveatedRendering : -1);
  const bool quad = has_quad && !o.stereo;
  const bool foveated = quad && fov_ext && o.foveated;
  const XrViewConfigurationType config = quad ? XR_VIEW_CONFIGURATION_TYPE_PRIMARY_QUAD_VARJO : XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;

  std::uint32_t nv = 0;
  CHECK(xrEnumerateViewConfigurationViews(g_instance, system, config, 0, &nv, nullptr));
  std::vector<XrViewConfigurationView> cviews(nv, {XR_TYPE_VIEW_CONFIGURATION_VIEW});
  std::vector<XrFoveatedViewConfigurationViewVARJO> fviews(nv, {XR_TYPE_FOVEATED_VIEW_CONFIGURATION_VIEW_VARJO});
  for (std::uint32_t i = 0; i < nv && foveated; ++i) fviews[i].foveatedRenderingActive = XR_TRUE, cviews[i].next = &fviews[i];
  CHECK(xrEnumerateViewConfigurationViews(g_instance, system, config, nv, &nv, cviews.data()));
  std::string sizes;
  for (const auto& v : cviews)
    sizes += (sizes.empty() ? "[" : ",[") + std::to_string(v.recommendedImageRectWidth) + "," +
             std::to_string(v.recommendedImageRectHeight) + "]";
  std::printf("{\"event\":\"views\",\"configuration\":\"%s\",\"foveated\":%s,\"sizes\":[%s]}\n", quad ? "quad" : "stereo",
              foveated ? "true" : "false", sizes.c_str());
  std::fflush(stdout);

  XrGraphicsRequirementsOpenGLKHR req{XR_TYPE_GRAPHICS_REQUIREMENTS_OPENGL_KHR};
  CHECK(proc<PFN_xrGetOpenGLGraphicsRequirementsKHR>("xrGetOpenGLGraphicsRequirementsKHR")(g_instance, system, &req));
  EGLDisplay display = eglGetCurrentDisplay();
  EGLContext context = eglGetCurrentContext();
  EGLint config_id = 0, n_configs = 0;
  EGLConfig egl_config = nullptr;
  eglQueryContext(display, context, EGL_CONFIG_ID, &config_id);
  const EGLint by_id[] = {EGL_CONFIG_ID, config_id, EGL_NONE};
  if (config_id > 0) eglChooseConfig(display, by_id, &egl_config, 1, &n_configs);
  XrGraphicsBindingEGLMNDX binding{XR_TYPE_GRAPHICS_BINDING_EGL_MNDX, nullptr, eglGetProcAddress, display,
                                   n_configs > 0 ? egl_config : nullptr, context};
  XrSessionCreateInfo si{XR_TYPE_SESSION_CREATE_INFO, &binding, 0, system};
  XrSession session = XR_NULL_HANDLE;
  CHECK(xrCreateSession(g_instance, &si, &session));
  XrReferenceSpaceCreateInfo rs{XR_TYPE_REFERENCE_SPACE_CREATE_INFO, nullptr, XR_REFERENCE_SPACE_TYPE_LOCAL, {{0, 0, 0, 1}, {0, 0, 0}}};
  XrSpace local = XR_NULL_HANDLE;
  CHECK(xrCreateReferenceSpace(session, &rs, &local));
  std::unique_ptr<example::GazeReader> gaze;
  if (o.gaze && !(gaze = example::GazeReader::create(g_instance, session))) return 1;

  std::uint32_t nf = 0;
  CHECK(xrEnumerateSwapchainFormats(session, 0, &nf, nullptr));
  std::vector<std::int64_t> formats(nf);
  CHECK(xrEnumerateSwapchainFormats(session, nf, &nf, formats.data()));
  std::int64_t format = formats.empty() ? GL_SRGB8_ALPHA8 : formats[0];
  for (auto f : formats)
    if (f == GL_SRGB8_ALPHA8) format = f;
  // One swapchain a view, or with --array one for all, its layers the largest view's size.
  std::vector<ViewTarget> targets(o.array ? 1 : nv);
  for (std::uint32_t i = 0; i < targets.size(); ++i) {
    ViewTarget& t = targets[i];
    t.width = static_cast<int>(cviews[i].recommendedImageRectWidth);
    t.height = static_cast<int>(cviews[i].recommendedImageRectHeight);
    for (std::uint32_t j = 0; j < nv && o.array; ++j) {
      t.width = std::max(t.width, static_cast<int>(cviews[j].recommendedImageRectWidth));
      t.height = std::max(t.height, static_cast<int>(cviews[j].recommendedImageRectHeight));
    }
    XrSwapchainCreateInfo sc{XR_TYPE_SWAPCHAIN_CREATE_INFO, nullptr, 0,
                             XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT | XR_SWAPCHAIN_USAGE_SAMPLED_BIT, format, 1,
                             static_cast<std::uint32_t>(t.width), static_cast<std::uint32_t>(t.height), 1,
                             o.array ? nv : 1u, 1};
    CHECK(xrCreateSwapchain(session, &sc, &t.swapchain));
    std::uint32_t ni = 0;
    CHECK(xrEnumerateSwapchainImages(t.swapchain, 0, &ni, nullptr));
    t.images.assign(ni, {XR_TYPE_SWAPCHAIN_IMAGE_OPENGL_KHR});
    CHECK(xrEnumerateSwapchainImages(t.swapchain, ni, &ni, reinterpret_cast<XrSwapchainImageBaseHeader*>(t.images.data())));
  }

  bool running = false, exit_requested = false;
  int frame = 0;
  std::vector<XrView> views(nv, {XR_TYPE_VIEW});
  std::vector<XrCompositionLayerProjectionView> pviews(nv, {XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW});
  for (;;) {
    XrEventDataBuffer ev{XR_TYPE_EVENT_DATA_BUFFER};
    bool exiting = false;
    while (xrPollEvent(g_instance, &ev) == XR_SUCCESS) {
      if (ev.type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) {
        const auto state = reinterpret_cast<XrEventDataSessionStateChanged*>(&ev)->state;
        if (state == XR_SESSION_STATE_READY) {
          XrSessionBeginInfo bi{XR_TYPE_SESSION_BEGIN_INFO, nullptr, config};
          CHECK(xrBeginSession(session, &bi));
          running = true;
        } else if (state == XR_SESSION_STATE_STOPPING) {
          CHECK(xrEndSession(session));
          running = false;
        } else if (state == XR_SESSION_STATE_EXITING || state == XR_SESSION_STATE_LOSS_PENDING) {
          exiting = true;
        }
      }
      ev = {XR_TYPE_EVENT_DATA_BUFFER};
    }
    if (exiting) break;
    if (!running) {
      timespec pause{0, 5'000'000};
      nanosleep(&pause, nullptr);
      continue;
    }
    XrFrameState fs{XR_TYPE_FRAME_STATE};
    CHECK(xrWaitFrame(session, nullptr, &fs));
    CHECK(xrBeginFrame(session, nullptr));
    XrViewLocateFoveatedRenderingVARJO vf{XR_TYPE_VIEW_LOCATE_FOVEATED_RENDERING_VARJO, nullptr, XR_TRUE};
    XrViewLocateInfo li{XR_TYPE_VIEW_LOCATE_INFO, foveated ? &vf : nullptr, config, fs.predictedDisplayTime, local};
    XrViewState vs{XR_TYPE_VIEW_STATE};
    std::uint32_t located = 0;
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    const std::int64_t locate_ns = static_cast<std::int64_t>(now.tv_sec) * 1000000000 + now.tv_nsec;
    if (gaze && !gaze->sync()) {
      std::fprintf(stderr, "openxr_quad_views: xrSyncActions failed\n");
      return 1;
    }
    CHECK(xrLocateViews(session, &li, &vs, nv, &located, views.data()));
    std::string line = "{\"event\":\"frame\",\"i\":" + std::to_string(frame) +
                       ",\"display_ns\":" + std::to_string(mono_of(fs.predictedDisplayTime)) +
                       ",\"locate_ns\":" + std::to_string(locate_ns);
    if (gaze) {
      const example::GazeReading r = gaze->read(local, fs.predictedDisplayTime);
      line += std::string(",\"gaze\":{\"active\":") + (r.active ? "true" : "false") +
              ",\"tracked\":" + (r.tracked ? "true" : "false") +
              ",\"sample_ns\":" + std::to_string(r.sample_time ? mono_of(r.sample_time) : 0) + "}";
    }
    line += ",\"views\":[";
    std::uint32_t index = 0;
    for (std::uint32_t i = 0; i < nv; ++i) {
      ViewTarget& t = targets[o.array ? 0 : i];
      const int w = static_cast<int>(cviews[i].recommendedImageRectWidth);
      const int h = static_cast<int>(cviews[i].recommendedImageRectHeight);
      const int layer = o.array ? static_cast<int>(i) : -1;
      if (!o.array || i == 0) {  // an array swapchain's one image holds every view
        XrSwapchainImageAcquireInfo ai{XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO};
        CHECK(xrAcquireSwapchainImage(t.swapchain, &ai, &index));
        XrSwapchainImageWaitInfo wi{XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO, nullptr, XR_INFINITE_DURATION};
        CHECK(xrWaitSwapchainImage(t.swapchain, &wi));
      }
      const XrPosef& p = views[i].pose;
      glm::mat4 eye = glm::mat4_cast(glm::quat(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z));
      eye[3] = glm::vec4(p.position.x, p.position.y, p.position.z, 1.0f);
      if (o.still) eye = glm::translate(glm::mat4(1.0f), glm::vec3(i % 2 == 0 ? -0.032f : 0.032f, 0.0f, 0.0f));
      const XrFovf& f = views[i].fov;
      renderer->draw(t.images[index].image, w, h,
                     {eye, std::tan(f.angleLeft), std::tan(f.angleRight), std::tan(f.angleDown), std::tan(f.angleUp)},
                     layer);
      if (frame == o.save_frame && !o.save_dir.empty() &&
          !save_view(t.images[index].image, std::max(layer, 0), w, h,
                     o.save_dir + "/view_" + std::to_string(i) + ".png")) {
        std::fprintf(stderr, "openxr_quad_views: cannot write %s/view_%u.png\n", o.save_dir.c_str(), i);
        return 1;
      }
      if (!o.array || i + 1 == nv) {
        XrSwapchainImageReleaseInfo ri{XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO};
        CHECK(xrReleaseSwapchainImage(t.swapchain, &ri));
      }
      pviews[i] = {XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW, nullptr, p, f,
                   {t.swapchain, {{0, 0}, {w, h}}, static_cast<std::uint32_t>(std::max(layer, 0))}};
      char v[320];
      std::snprintf(v, sizeof v, "%s{\"fov\":[%.7f,%.7f,%.7f,%.7f],\"q\":[%.7f,%.7f,%.7f,%.7f],\"p\":[%.6f,%.6f,%.6f],\"size\":[%d,%d]}",
                    i ? "," : "", f.angleLeft, f.angleRight, f.angleUp, f.angleDown, p.orientation.x, p.orientation.y,
                    p.orientation.z, p.orientation.w, p.position.x, p.position.y, p.position.z, w, h);
      line += v;
    }
    XrCompositionLayerProjection layer{XR_TYPE_COMPOSITION_LAYER_PROJECTION, nullptr, 0, local, nv, pviews.data()};
    const XrCompositionLayerBaseHeader* layers[] = {reinterpret_cast<XrCompositionLayerBaseHeader*>(&layer)};
    XrFrameEndInfo fe{XR_TYPE_FRAME_END_INFO, nullptr, fs.predictedDisplayTime, XR_ENVIRONMENT_BLEND_MODE_OPAQUE,
                      fs.shouldRender ? 1u : 0u, layers};
    CHECK(xrEndFrame(session, &fe));
    std::printf("%s]}\n", line.c_str());
    std::fflush(stdout);
    if (++frame >= o.frames && !exit_requested) {
      CHECK(xrRequestExitSession(session));
      exit_requested = true;
    }
  }
  gaze.reset();
  for (auto& t : targets) xrDestroySwapchain(t.swapchain);
  xrDestroySpace(local);
  xrDestroySession(session);
  xrDestroyInstance(g_instance);
  std::printf("{\"event\":\"end\",\"frames\":%d}\n", frame);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const char* what) -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "openxr_quad_views: %s needs a value\n", what);
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--help" || a == "-h") return usage(0);
    if (a == "--scene") o.scene = value("--scene");
    else if (a == "--frames") o.frames = std::atoi(value("--frames"));
    else if (a == "--stereo") o.stereo = true;
    else if (a == "--no-foveated") o.foveated = false;
    else if (a == "--still") o.still = true;
    else if (a == "--gaze") o.gaze = true;
    else if (a == "--array") o.array = true;
    else if (a == "--save-dir") o.save_dir = value("--save-dir");
    else if (a == "--save-frame") o.save_frame = std::atoi(value("--save-frame"));
    else return usage(2);
  }
  if (o.frames < 1) return usage(2);
  return run(o);
}

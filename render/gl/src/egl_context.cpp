#include "foveal/render/egl_context.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>

#include "foveal/render/egl_util.hpp"
#include "foveal/render/gl.hpp"

namespace foveal::gl {

struct EglContext::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  ~Impl() {
    if (display == EGL_NO_DISPLAY) return;
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
    eglTerminate(display);
  }
};

namespace {

// Surfaceless (Mesa) first, then the first EGL device (drivers without it).
EGLDisplay open_display() {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_platform_display) return EGL_NO_DISPLAY;
  if (has_extension(client, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) return d;
  }
  if (has_extension(client, "EGL_EXT_platform_device")) {
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    EGLDeviceEXT devices[8];
    EGLint count = 0;
    if (query_devices && query_devices(8, devices, &count)) {
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) return d;
      }
    }
  }
  return EGL_NO_DISPLAY;
}

}  // namespace

Result<EglContext> EglContext::create() {
  auto impl = std::make_unique<Impl>();
  impl->display = open_display();
  if (impl->display == EGL_NO_DISPLAY)
    return Error{ErrorKind::unsupported,
                 "EGL: no headless display (needs EGL_MESA_platform_surfaceless or EGL_EXT_platform_device; "
                 "on Debian install libegl-mesa0 and libgl1-mesa-dri)"};
  if (!eglBindAPI(EGL_OPENGL_API)) return Error{ErrorKind::unsupported, egl_error("eglBindAPI(EGL_OPENGL_API)")};

  const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint n = 0;
  if (!eglChooseConfig(impl->display, config_attribs, &config, 1, &n) || n == 0) config = nullptr;
  const char* dpy_ext = eglQueryString(impl->display, EGL_EXTENSIONS);
  if (!config && !has_extension(dpy_ext, "EGL_KHR_no_config_context"))
    return Error{ErrorKind::unsupported, "EGL: no config with OpenGL support"};
  if (!has_extension(dpy_ext, "EGL_KHR_surfaceless_context"))
    return Error{ErrorKind::unsupported, "EGL: the display lacks EGL_KHR_surfaceless_context"};

  impl->context = eglCreateContext(impl->display, config ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, kGl45CoreAttribs);
  if (impl->context == EGL_NO_CONTEXT)
    return Error{ErrorKind::unsupported, egl_error("eglCreateContext (OpenGL 4.5 core)")};
  if (!eglMakeCurrent(impl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl->context))
    return Error{ErrorKind::unsupported, egl_error("eglMakeCurrent")};
  return EglContext(std::move(impl));
}

EglContext::EglContext(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
EglContext::EglContext(EglContext&&) noexcept = default;
EglContext& EglContext::operator=(EglContext&&) noexcept = default;
EglContext::~EglContext() = default;

std::string EglContext::description() const {
  auto str = [](GLenum e) {
    const auto* s = reinterpret_cast<const char*>(glGetString(e));
    return std::string(s ? s : "?");
  };
  return str(GL_VENDOR) + " / " + str(GL_RENDERER) + " / " + str(GL_VERSION);
}

bool EglContext::is_software() const {
  const auto* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return r && (std::strstr(r, "llvmpipe") || std::strstr(r, "softpipe"));
}

}  // namespace foveal::gl

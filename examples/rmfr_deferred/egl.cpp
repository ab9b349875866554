// A headless OpenGL 4.5 core context: EGL on Mesa's surfaceless platform, else the first
// EGL device (GPU drivers without a surfaceless platform).
#include "egl.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>

namespace {
EGLDisplay open_display() {
  auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_platform_display) return EGL_NO_DISPLAY;
  const char* ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (ext && std::strstr(ext, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) return d;
  }
  auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  EGLDeviceEXT device;
  EGLint n = 0;
  if (query_devices && query_devices(1, &device, &n) && n > 0) {
    EGLDisplay d = get_platform_display(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
    if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) return d;
  }
  return EGL_NO_DISPLAY;
}
}  // namespace

std::string make_headless_gl_context() {
  EGLDisplay d = open_display();
  if (d == EGL_NO_DISPLAY) return "no EGL display (surfaceless or device platform)";
  if (!eglBindAPI(EGL_OPENGL_API)) return "EGL has no desktop OpenGL";
  const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
                            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext c = eglCreateContext(d, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
  if (c == EGL_NO_CONTEXT) return "no OpenGL 4.5 core context";
  if (!eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, c)) return "eglMakeCurrent failed";
  return {};
}

#pragma once
// EGL helpers shared by the headless context (egl_context.cpp) and direct mode
// (render/output, drm_output.cpp).
#include <EGL/egl.h>

#include <cstdio>
#include <cstring>
#include <string>

namespace foveal::gl {

inline std::string egl_error(const char* call) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "%s failed (EGL error 0x%04x)", call, static_cast<unsigned>(eglGetError()));
  return buf;
}

/// Whether the space-separated extension `list` holds `name` exactly.
inline bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

/// Attributes of an OpenGL 4.5 core context, for eglCreateContext.
inline constexpr EGLint kGl45CoreAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                              EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                              EGL_NONE};

}  // namespace foveal::gl

#pragma once
// A headless OpenGL 4.5 core context through EGL, with no window and no display server:
// EGL_MESA_platform_surfaceless where available (Mesa; llvmpipe on machines without a
// GPU), else the EGL device platform (NVIDIA's driver). Rendering goes to framebuffer
// objects. The context is current on the creating thread; destroy it on that thread.
#include <memory>
#include <string>

#include "foveal/core/error.hpp"

namespace foveal::gl {

class EglContext {
 public:
  /// Creates and makes current a GL 4.5 core context. Errors name the EGL call that
  /// failed and what the driver said; ErrorKind::unsupported when no GL 4.5 is offered.
  static Result<EglContext> create();
  EglContext(EglContext&&) noexcept;
  EglContext& operator=(EglContext&&) noexcept;
  ~EglContext();

  /// "vendor / renderer / version" of the current context.
  std::string description() const;
  /// True when the renderer is Mesa's software rasteriser (llvmpipe or softpipe).
  bool is_software() const;

 private:
  struct Impl;
  explicit EglContext(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace foveal::gl

#pragma once
// Where the compositor's frames go: one interface for every output (headless EGL, a
// GLFW window, DRM/KMS direct mode), so a program renders the same way whatever the
// output and a new output is one new file in render/output/src (plus its line in
// open_output()).
// Thread safety: create, use and destroy an output on one thread (the thread whose GL
// context it made current; GLFW's rule makes that the main thread for windows).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/core/error.hpp"
#include "foveal/render/drm_output.hpp"
#include "foveal/render/gl.hpp"

namespace foveal::render {

class Output {
 public:
  virtual ~Output() = default;
  /// "headless", "window" or "drm".
  virtual const char* kind() const = 0;
  /// Shows `framebuffer` (width×height). Headless: nothing to show. Errors: direct mode's
  /// lost DRM master or a flip that never completed.
  virtual Status present(GLuint framebuffer, int width, int height) = 0;
  /// Waits until the last presented frame is on screen (so stats count it).
  virtual Status finish() { return {}; }
  /// The user closed the window.
  virtual bool closed() const { return false; }
  /// When the frames presented since the last call reached the screen (CLOCK_MONOTONIC),
  /// oldest first, each frame once; a frame whose time is not known yet (a page flip
  /// still pending) comes in a later call, at the latest after finish(). How the time is
  /// taken: shown_clock().
  virtual std::vector<std::int64_t> take_shown() = 0;
  /// "page_flip": the kernel's flip-completion timestamp (direct mode); "swap": when the
  /// buffer swap returned (a window: GLFW has no presentation time); "gpu_done": when
  /// present() was called after the GPU finished the frame (headless, a proxy).
  virtual const char* shown_clock() const = 0;
  /// When the last presented frame was ready to show (copied to the display's buffer and
  /// swapped), before any wait for a refresh: what a frame costs until it can be shown,
  /// for pacing. CLOCK_MONOTONIC; 0 before the first present.
  virtual std::int64_t last_ready_ns() const = 0;
  /// kind, and what was presented (PresentStats) and where, for status and summaries.
  virtual nlohmann::json json() const = 0;
};

struct OutputOptions {
  enum class Kind { headless, window, drm } kind = Kind::headless;
  std::string monitor;          ///< window: fullscreen on this monitor ("" windowed)
  std::string title = "foveal"; ///< window title
  DrmOutputOptions drm;         ///< direct mode: card, connector, mode
};

/// Opens the output with an OpenGL 4.5 core context current on this thread. Errors:
/// those of EglContext::create, Window::open and DrmOutput::open.
Result<std::unique_ptr<Output>> open_output(const OutputOptions& options);

}  // namespace foveal::render

#pragma once
// An on-screen output through GLFW: a window, or fullscreen on a named monitor (the
// HMD's, for a tethered headset), with an OpenGL 4.5 core context and vsync. The
// compositor renders into its own framebuffer; present() blits that to the window.
// Create, use and destroy on one thread (GLFW's main-thread rule).
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "foveal/core/error.hpp"
#include "foveal/render/gl.hpp"
#include "foveal/render/present_stats.hpp"

namespace foveal::render {

struct WindowOptions {
  int width = 1440, height = 800;  ///< window size (ignored when fullscreen)
  /// Windowed: a size larger than the primary monitor shrinks to fit it, keeping its
  /// aspect (a window partly off the screen would hide part of the picture).
  bool fit_to_monitor = false;
  std::string monitor;             ///< fullscreen on the monitor whose name contains this; empty: windowed
  bool vsync = true;
  std::string title = "foveal";
};

class Window {
 public:
  /// Errors: no display (GLFW could not initialise), no monitor matching the name (the
  /// message lists the connected ones), no GL 4.5 core context.
  static Result<Window> open(const WindowOptions& options);
  Window(Window&&) noexcept;
  Window& operator=(Window&&) noexcept;
  ~Window();

  /// Blits `framebuffer` (width×height) scaled to the window, swaps, polls events.
  void present(GLuint framebuffer, int width, int height);
  /// Frames presented and refreshes missed, judged from the time each swap returned
  /// against the monitor's refresh rate (GLFW has no presentation timestamps).
  const PresentStats& stats() const;
  /// The swaps' return times since the last call, oldest first.
  std::vector<std::int64_t> take_shown();
  /// When the last frame was copied to the back buffer, before the swap (which may wait
  /// for vsync).
  std::int64_t last_ready_ns() const;
  bool should_close() const;
  /// The window's framebuffer in pixels: what present() scales each frame to.
  std::pair<int, int> framebuffer_size() const;
  /// Keys pressed since the last call (GLFW key codes), for interactive tools.
  std::vector<int> take_keys();

  /// Names of the connected monitors (initialises GLFW if needed).
  static Result<std::vector<std::string>> monitors();

 private:
  struct Impl;
  explicit Window(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace foveal::render

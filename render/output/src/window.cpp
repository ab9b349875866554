#include "foveal/render/window.hpp"

#include <algorithm>

#include "foveal/core/clock.hpp"

#define GLFW_INCLUDE_NONE  // GL comes from foveal/render/gl.hpp (core profile)
#include <GLFW/glfw3.h>


namespace foveal::render {

namespace {

std::string glfw_error() {
  const char* desc = nullptr;
  glfwGetError(&desc);
  return desc ? desc : "unknown GLFW error";
}

Status init_glfw() {
  static bool ok = false;
  if (!ok && !glfwInit()) return Error{ErrorKind::unsupported, "no display for a window: " + glfw_error()};
  ok = true;
  return {};
}

}  // namespace

struct Window::Impl {
  GLFWwindow* window = nullptr;
  std::vector<int> keys;
  PresentStats stats;
  std::int64_t ready_ns = 0;
  ~Impl() {
    if (window) glfwDestroyWindow(window);
  }
};

Result<std::vector<std::string>> Window::monitors() {
  if (Status s = init_glfw(); !s) return s.error();
  int count = 0;
  GLFWmonitor** list = glfwGetMonitors(&count);
  std::vector<std::string> names;
  for (int i = 0; i < count; ++i) names.emplace_back(glfwGetMonitorName(list[i]));
  return names;
}

Result<Window> Window::open(const WindowOptions& o) {
  if (Status s = init_glfw(); !s) return s.error();
  GLFWmonitor* monitor = nullptr;
  if (!o.monitor.empty()) {
    int count = 0;
    GLFWmonitor** list = glfwGetMonitors(&count);
    std::string names;
    for (int i = 0; i < count && !monitor; ++i) {
      const std::string name = glfwGetMonitorName(list[i]);
      if (name.find(o.monitor) != std::string::npos) monitor = list[i];
      names += (names.empty() ? "" : ", ") + name;
    }
    if (!monitor) return bad_input("no monitor named '" + o.monitor + "' (connected: " + (names.empty() ? "none" : names) + ")");
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  int w = o.width, h = o.height;
  if (monitor) {
    const GLFWvidmode* mode = glfwGetVideoMode(monitor);
    w = mode->width;
    h = mode->height;
    glfwWindowHint(GLFW_REFRESH_RATE, mode->refreshRate);
  } else if (GLFWmonitor* primary = glfwGetPrimaryMonitor(); o.fit_to_monitor && primary) {
    if (const GLFWvidmode* mode = glfwGetVideoMode(primary); mode && (w > mode->width || h > mode->height)) {
      const double k = std::min(static_cast<double>(mode->width) / w, static_cast<double>(mode->height) / h);
      w = std::max(1, static_cast<int>(w * k));
      h = std::max(1, static_cast<int>(h * k));
    }
  }
  auto impl = std::make_unique<Impl>();
  impl->window = glfwCreateWindow(w, h, o.title.c_str(), monitor, nullptr);
  if (!impl->window) return Error{ErrorKind::unsupported, "cannot create an OpenGL 4.5 core window: " + glfw_error()};
  glfwMakeContextCurrent(impl->window);
  glfwSwapInterval(o.vsync ? 1 : 0);
  // Missed refreshes only mean something with vsync, at the rate of the monitor shown on.
  if (GLFWmonitor* m = monitor ? monitor : glfwGetPrimaryMonitor(); m && o.vsync)
    if (const GLFWvidmode* vm = glfwGetVideoMode(m)) impl->stats = PresentStats(vm->refreshRate);
  glfwSetWindowUserPointer(impl->window, impl.get());
  glfwSetKeyCallback(impl->window, [](GLFWwindow* win, int key, int, int action, int) {
    if (action == GLFW_PRESS) static_cast<Impl*>(glfwGetWindowUserPointer(win))->keys.push_back(key);
  });
  return Window(std::move(impl));
}

Window::Window(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Window::Window(Window&&) noexcept = default;
Window& Window::operator=(Window&&) noexcept = default;
Window::~Window() = default;

void Window::present(GLuint framebuffer, int width, int height) {
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(impl_->window, &fw, &fh);
  glDisable(GL_FRAMEBUFFER_SRGB);  // copy the sRGB-encoded bytes as they are
  glBlitNamedFramebuffer(framebuffer, 0, 0, 0, width, height, 0, 0, fw, fh, GL_COLOR_BUFFER_BIT, GL_LINEAR);
  glFinish();  // the copy's cost belongs to the frame, not to the swap's wait
  impl_->ready_ns = monotonic_now_ns();
  glfwSwapBuffers(impl_->window);
  impl_->stats.record(monotonic_now_ns());
  glfwPollEvents();
}

const PresentStats& Window::stats() const { return impl_->stats; }
std::vector<std::int64_t> Window::take_shown() { return impl_->stats.take_shown(); }
std::int64_t Window::last_ready_ns() const { return impl_->ready_ns; }

std::pair<int, int> Window::framebuffer_size() const {
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(impl_->window, &fw, &fh);
  return {fw, fh};
}

bool Window::should_close() const { return glfwWindowShouldClose(impl_->window) != 0; }

std::vector<int> Window::take_keys() {
  std::vector<int> k;
  k.swap(impl_->keys);
  return k;
}

}  // namespace foveal::render

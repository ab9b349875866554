// A GLFW window (fullscreen on a monitor when asked).
#include "foveal/render/window.hpp"
#include "output_kinds.hpp"

namespace foveal::render {

namespace {

class WindowOutput final : public Output {
 public:
  explicit WindowOutput(Window w) : window_(std::move(w)) {}
  const char* kind() const override { return "window"; }
  Status present(GLuint framebuffer, int width, int height) override {
    window_.present(framebuffer, width, height);
    return {};
  }
  bool closed() const override { return window_.should_close(); }
  std::vector<std::int64_t> take_shown() override { return window_.take_shown(); }
  const char* shown_clock() const override { return "swap"; }
  std::int64_t last_ready_ns() const override { return window_.last_ready_ns(); }
  nlohmann::json json() const override { return {{"kind", kind()}, {"present", window_.stats().json()}}; }

 private:
  Window window_;
};

}  // namespace

Result<std::unique_ptr<Output>> open_window_output(const OutputOptions& o) {
  WindowOptions wo;
  wo.monitor = o.monitor;
  wo.title = o.title;
  auto w = Window::open(wo);
  if (!w) return w.error();
  return std::unique_ptr<Output>(new WindowOutput(std::move(*w)));
}

}  // namespace foveal::render

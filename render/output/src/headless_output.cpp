// Headless: a surfaceless EGL context; frames stay in the compositor's framebuffer.
#include "foveal/core/clock.hpp"
#include "foveal/render/egl_context.hpp"
#include "output_kinds.hpp"

namespace foveal::render {

namespace {

class HeadlessOutput final : public Output {
 public:
  explicit HeadlessOutput(gl::EglContext ctx) : ctx_(std::move(ctx)) {}
  const char* kind() const override { return "headless"; }
  Status present(GLuint, int, int) override {
    // The compositor waited for the GPU before: now is when the frame was done.
    ready_ = monotonic_now_ns();
    shown_.push_back(ready_);
    return {};
  }
  std::int64_t last_ready_ns() const override { return ready_; }
  std::vector<std::int64_t> take_shown() override {
    std::vector<std::int64_t> t;
    t.swap(shown_);
    return t;
  }
  const char* shown_clock() const override { return "gpu_done"; }
  nlohmann::json json() const override { return {{"kind", kind()}}; }

 private:
  gl::EglContext ctx_;
  std::vector<std::int64_t> shown_;
  std::int64_t ready_ = 0;
};

}  // namespace

Result<std::unique_ptr<Output>> open_headless_output() {
  auto ctx = gl::EglContext::create();
  if (!ctx) return ctx.error();
  return std::unique_ptr<Output>(new HeadlessOutput(std::move(*ctx)));
}

}  // namespace foveal::render

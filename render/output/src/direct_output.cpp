// Direct mode: a DRM/KMS connector through EGL on GBM (drm_output.cpp does the work).
#include "foveal/render/kms_select.hpp"
#include "output_kinds.hpp"

namespace foveal::render {

namespace {

class DirectOutput final : public Output {
 public:
  explicit DirectOutput(DrmOutput d) : drm_(std::move(d)) {}
  const char* kind() const override { return "drm"; }
  Status present(GLuint framebuffer, int width, int height) override { return drm_.present(framebuffer, width, height); }
  Status finish() override { return drm_.finish(); }
  std::vector<std::int64_t> take_shown() override { return drm_.take_shown(); }
  const char* shown_clock() const override { return "page_flip"; }
  std::int64_t last_ready_ns() const override { return drm_.last_ready_ns(); }
  nlohmann::json json() const override {
    const KmsMode& m = drm_.mode();
    nlohmann::json connector = connector_json(drm_.connector());
    connector.erase("modes");  // `foveal outputs` lists them
    return {{"kind", kind()},
            {"device", drm_.device()},
            {"connector", connector},
            {"mode", {{"width", m.width}, {"height", m.height}, {"refresh_hz", m.refresh_hz}}},
            {"present", drm_.stats().json()}};
  }

 private:
  DrmOutput drm_;
};

}  // namespace

Result<std::unique_ptr<Output>> open_drm_output(const OutputOptions& o) {
  auto d = DrmOutput::open(o.drm);
  if (!d) return d.error();
  return std::unique_ptr<Output>(new DirectOutput(std::move(*d)));
}

Result<std::unique_ptr<Output>> open_output(const OutputOptions& o) {
  switch (o.kind) {
    case OutputOptions::Kind::window: return open_window_output(o);
    case OutputOptions::Kind::drm: return open_drm_output(o);
    case OutputOptions::Kind::headless: break;
  }
  return open_headless_output();
}

}  // namespace foveal::render

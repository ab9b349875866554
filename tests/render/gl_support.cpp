#include "gl_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <optional>

#include "test_support.hpp"

namespace foveal::test {

bool gl_ready() {
  static std::optional<Result<gl::EglContext>> ctx;
  if (!ctx) ctx.emplace(gl::EglContext::create());
  if (!ctx->ok()) ADD_FAILURE() << "no OpenGL 4.5 context: " << ctx->error().message;
  return ctx->ok();
}

gl::ShaderLoader source_shaders() { return gl::ShaderLoader(source_path("shaders")); }

render::Compositor make_compositor(int width, int height, bool float_output) {
  render::CompositorOptions o;
  o.width = width;
  o.height = height;
  o.float_output = float_output;
  o.shadow_map_size = 1024;
  auto c = render::Compositor::create(o, source_shaders());
  if (!c) {
    ADD_FAILURE() << c.error().message;
    std::abort();
  }
  return std::move(*c);
}

render::Scene scene(const std::string& spec) {
  auto s = render::load_scene(spec);
  if (!s) {
    ADD_FAILURE() << s.error().message;
    std::abort();
  }
  return std::move(*s);
}

image::Image render_frame(render::Compositor& c, const render::Scene& s, const render::FrameParams& p) {
  auto t = c.render(s, p);
  EXPECT_TRUE(t) << (t ? "" : t.error().message);
  return c.read_image();
}

render::FrameParams frame(render::Method m, double sigma, double x, double y) {
  render::FrameParams p;
  p.method = m;
  for (auto& e : p.eyes) e = {sigma, 0.3, 0.3, x, y};
  return p;
}

void expect_matches_golden(const image::Image& img, const std::string& name, double min_psnr_db) {
  const std::string golden = source_path("tests/render/golden/" + name + ".png");
  if (const char* u = std::getenv("FOVEAL_UPDATE_GOLDEN"); u && std::string(u) == "1") {
    ASSERT_TRUE(image::save_png(golden, img));
    return;
  }
  auto ref = image::load(golden);
  ASSERT_TRUE(ref) << ref.error().message << " (FOVEAL_UPDATE_GOLDEN=1 writes it)";
  ASSERT_EQ(ref->width, img.width);
  ASSERT_EQ(ref->height, img.height);
  const double p = image::psnr(*ref, img);
  if (p >= min_psnr_db) return;
  const std::string dir = std::string(FOVEAL_BIN_DIR) + "/../test-output";
  std::filesystem::create_directories(dir);
  (void)image::save_png(dir + "/" + name + ".actual.png", img);
  (void)image::save_png(dir + "/" + name + ".diff.png", image::diff_image(*ref, img));
  ADD_FAILURE() << name << ": PSNR " << p << " dB against the golden image, below " << min_psnr_db
                << " dB; max difference " << image::max_abs_diff(*ref, img) << "; see " << dir << "/" << name
                << ".{actual,diff}.png";
}

image::Rect fovea_patch(const render::Compositor& c, Eye e, double x, double y, int size) {
  const int w = c.eye_width(), h = c.height();
  const int cx = static_cast<int>(x * w), cy = static_cast<int>(y * h);
  const int x0 = std::clamp(cx - size / 2, 0, w), y0 = std::clamp(cy - size / 2, 0, h);
  const int x1 = std::clamp(cx + size / 2, 0, w), y1 = std::clamp(cy + size / 2, 0, h);
  const int offset = e == Eye::left ? 0 : w;
  return {x0 + offset, y0, x1 - x0, y1 - y0};
}

}  // namespace foveal::test

// The OpenXR layer's Vulkan composer against its GL composer and against the math on the
// CPU (issue 37, 5f): the same four views uploaded to both, composed, read back. Monado
// here takes no Vulkan client (lavapipe lacks VK_KHR_external_semaphore_fd), so this runs
// the composers alone: GL on an EGL surfaceless context (llvmpipe), Vulkan on the first
// CPU device (lavapipe). docs/openxr.md, "Quad views".
#include <EGL/egl.h>
#include <gtest/gtest.h>
#include <vulkan/vulkan.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "foveal/render/egl_context.hpp"
#include "foveal/render/gl.hpp"
#include "gl_composer.hpp"
#include "vk_composer.hpp"
#include "vk_headless.hpp"

namespace foveal::openxr {
namespace {

// One eye: 320×256 output pixels over tangents [-1, 1] × [-0.8, 0.8], 0.00625 a pixel.
constexpr int kW = 320, kH = 256;
constexpr TanRect kOut{-1.0f, 1.0f, -0.8f, 0.8f};
// The inner view at full density on the output's pixel grid: 112×96 pixels from column
// 176, row 64 (from the top), so that away from the band each output pixel is one texel.
constexpr TanRect kInner{0.1f, 0.8f, -0.2f, 0.4f};
constexpr float kBandDeg = 3.0f;

/// An image inside a larger one (a sub-image rectangle, stated from the upper left).
struct View {
  int image_w, image_h, x, y, w, h;
  TanRect fov;
  std::vector<std::uint8_t> rgba;  // image_w × image_h, top row first
};

View noise_view(int image_w, int image_h, int x, int y, int w, int h, const TanRect& fov, std::uint32_t seed) {
  View v{image_w, image_h, x, y, w, h, fov, std::vector<std::uint8_t>(static_cast<std::size_t>(image_w * image_h * 4))};
  std::uint32_t s = seed;
  for (std::size_t i = 0; i < v.rgba.size(); ++i) {
    s = s * 1664525u + 1013904223u;
    v.rgba[i] = (i % 4 == 3) ? 255 : static_cast<std::uint8_t>(s >> 24);
  }
  return v;
}

double to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
double to_srgb(double l) { return l <= 0.0031308 ? l * 12.92 : 1.055 * std::pow(l, 1 / 2.4) - 0.055; }

/// Bilinear lookup, clamped to the edge of the view's rectangle (compose.glsl's inside()),
/// in linear light (an sRGB texture), of the point u, v in [0,1] of that rectangle, v up.
void sample(const View& view, double u, double v, double out[4]) {
  const double px = std::clamp(view.x + u * view.w - 0.5, double(view.x), double(view.x + view.w - 1));
  const double py = std::clamp(view.y + (1 - v) * view.h - 0.5, double(view.y), double(view.y + view.h - 1));
  const int x0 = static_cast<int>(std::floor(px)), y0 = static_cast<int>(std::floor(py));
  const double fx = px - x0, fy = py - y0;
  for (int c = 0; c < 4; ++c) out[c] = 0;
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      const int xx = std::min(x0 + dx, view.x + view.w - 1), yy = std::min(y0 + dy, view.y + view.h - 1);
      const double wgt = (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy);
      const std::uint8_t* p = &view.rgba[static_cast<std::size_t>((yy * view.image_w + xx) * 4)];
      for (int c = 0; c < 3; ++c) out[c] += wgt * to_linear(p[c] / 255.0);
      out[3] += wgt * p[3] / 255.0;
    }
}

/// The inner view's edge distance in radians at tangent (tx, ty), as compose.glsl has it.
double edge_angle(double tx, double ty) {
  const double ax = std::atan(tx), ay = std::atan(ty);
  return std::min(std::min(ax - std::atan(kInner.left), std::atan(kInner.right) - ax),
                  std::min(ay - std::atan(kInner.down), std::atan(kInner.up) - ay));
}

/// compose.glsl's math in double precision: the reference both composers are held to.
std::vector<std::uint8_t> reference(const View& outer, const View& inner) {
  std::vector<std::uint8_t> out(static_cast<std::size_t>(kW * kH * 4));
  const double band = kBandDeg * M_PI / 180.0;
  for (int row = 0; row < kH; ++row)
    for (int col = 0; col < kW; ++col) {
      const double tx = kOut.left + (col + 0.5) / kW * (kOut.right - kOut.left);
      const double ty = kOut.up - (row + 0.5) / kH * (kOut.up - kOut.down);
      double c[4], ci[4];
      sample(outer, (tx - outer.fov.left) / (outer.fov.right - outer.fov.left),
             (ty - outer.fov.down) / (outer.fov.up - outer.fov.down), c);
      const double d = edge_angle(tx, ty);
      if (d > 0) {
        sample(inner, (tx - kInner.left) / (kInner.right - kInner.left), (ty - kInner.down) / (kInner.up - kInner.down),
               ci);
        const double k = std::clamp(d / band, 0.0, 1.0), s = k * k * (3 - 2 * k);
        for (int i = 0; i < 4; ++i) c[i] += (ci[i] - c[i]) * s;
      }
      std::uint8_t* p = &out[static_cast<std::size_t>((row * kW + col) * 4)];
      for (int i = 0; i < 3; ++i) p[i] = static_cast<std::uint8_t>(std::lround(std::clamp(to_srgb(c[i]), 0.0, 1.0) * 255));
      p[3] = static_cast<std::uint8_t>(std::lround(c[3] * 255));
    }
  return out;
}

struct Diff {
  int max_abs = 0;
  double psnr = 0;
};
Diff compare(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  Diff d;
  double se = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const int e = std::abs(int(a[i]) - int(b[i]));
    d.max_abs = std::max(d.max_abs, e);
    se += double(e) * e;
  }
  const double mse = se / static_cast<double>(a.size());
  d.psnr = mse == 0 ? 99.0 : 10 * std::log10(255.0 * 255.0 / mse);
  return d;
}

GLuint gl_texture(const View& v) {
  // OpenGL's rows run bottom-up: the same picture uploaded flipped.
  std::vector<std::uint8_t> flipped(v.rgba.size());
  const std::size_t row = static_cast<std::size_t>(v.image_w) * 4;
  for (int y = 0; y < v.image_h; ++y)
    std::copy_n(v.rgba.data() + static_cast<std::size_t>(v.image_h - 1 - y) * row, row,
                flipped.data() + static_cast<std::size_t>(y) * row);
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, 1, GL_SRGB8_ALPHA8, v.image_w, v.image_h);
  glTextureSubImage2D(t, 0, 0, 0, v.image_w, v.image_h, GL_RGBA, GL_UNSIGNED_BYTE, flipped.data());
  return t;
}

ComposeSource gl_source(const View& v, GLuint texture) {
  return {texture, GL_SRGB8_ALPHA8, 0, v.image_w, v.image_h, v.x, v.image_h - v.y - v.h, v.w, v.h, v.fov};
}

ComposeSource vk_source(const View& v, VkImage image, std::uint64_t serial) {
  return {reinterpret_cast<std::uint64_t>(image), VK_FORMAT_R8G8B8A8_SRGB, serial, v.image_w, v.image_h, v.x, v.y, v.w, v.h,
          v.fov};
}

/// An array image (a swapchain with arraySize > 1): `layers` noise layers of w×h, one
/// after another, top row first, into which views are copied.
struct ArrayImage {
  int w, h, layers;
  std::vector<std::uint8_t> rgba;
};

ArrayImage noise_array(int w, int h, int layers, std::uint32_t seed) {
  const View v = noise_view(w, h * layers, 0, 0, w, h * layers, kOut, seed);
  return {w, h, layers, v.rgba};
}

/// Copies the view's whole image into `layer` of `a` at (x, y); the view, as the layer's.
View put_in_layer(ArrayImage& a, int layer, int x, int y, const View& v) {
  for (int row = 0; row < v.image_h; ++row)
    std::copy_n(&v.rgba[static_cast<std::size_t>(row * v.image_w * 4)], v.image_w * 4,
                &a.rgba[static_cast<std::size_t>(((layer * a.h + y + row) * a.w + x) * 4)]);
  View in = v;
  in.image_w = a.w, in.image_h = a.h, in.x += x, in.y += y, in.rgba.clear();
  return in;
}

GLuint gl_array_texture(const ArrayImage& a) {
  std::vector<std::uint8_t> flipped(a.rgba.size());  // each layer bottom row first
  const std::size_t row = static_cast<std::size_t>(a.w) * 4;
  for (int l = 0; l < a.layers; ++l)
    for (int y = 0; y < a.h; ++y)
      std::copy_n(a.rgba.data() + static_cast<std::size_t>(l * a.h + a.h - 1 - y) * row, row,
                  flipped.data() + static_cast<std::size_t>(l * a.h + y) * row);
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &t);
  glTextureStorage3D(t, 1, GL_SRGB8_ALPHA8, a.w, a.h, a.layers);
  glTextureSubImage3D(t, 0, 0, 0, 0, a.w, a.h, a.layers, GL_RGBA, GL_UNSIGNED_BYTE, flipped.data());
  return t;
}

ComposeSource in_layer(ComposeSource s, std::uint32_t layer) {
  s.layer = layer;
  s.array = true;
  return s;
}

class VkComposerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto ctx = gl::EglContext::create();
    ASSERT_TRUE(ctx) << ctx.error().message;
    egl_ = std::make_unique<gl::EglContext>(std::move(*ctx));
    std::string error;
    vulkan_ = VkHeadless::create(error);
    if (!vulkan_) GTEST_SKIP() << "no Vulkan device to compose on: " << error;
    gl_composer_ = GlComposer::create([](const char* n) { return reinterpret_cast<void*>(eglGetProcAddress(n)); }, error);
    ASSERT_TRUE(gl_composer_) << error;
    vk_composer_ = VkComposer::create(vulkan_->binding(), error);
    ASSERT_TRUE(vk_composer_) << error;
    // Outer: half density over the whole output, inside a larger image; inner: full density.
    outer_ = noise_view(180, 140, 10, 6, kW / 2, kH / 2, kOut, 1);
    inner_ = noise_view(128, 100, 8, 2, 112, 96, kInner, 2);
  }
  void TearDown() override {
    vk_composer_.reset();  // before its device
    vulkan_.reset();
    gl_composer_.reset();  // before its context
  }

  std::vector<std::uint8_t> compose_gl() {
    const GLuint outer = gl_texture(outer_), inner = gl_texture(inner_);
    std::vector<std::uint8_t> rgba = compose_gl(gl_source(outer_, outer), gl_source(inner_, inner));
    const GLuint all[2] = {outer, inner};
    glDeleteTextures(2, all);
    return rgba;
  }
  std::vector<std::uint8_t> compose_gl(const ComposeSource& outer, const ComposeSource& inner) {
    GLuint target = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &target);
    glTextureStorage2D(target, 1, GL_SRGB8_ALPHA8, kW, kH);
    const ComposeTarget t{target, GL_SRGB8_ALPHA8, 0, kW, kH};
    EXPECT_TRUE(gl_composer_->compose(outer, inner, t, kOut, kBandDeg));
    std::vector<std::uint8_t> rgba;
    EXPECT_TRUE(gl_composer_->read(t, rgba));
    glDeleteTextures(1, &target);
    return rgba;
  }

  /// Composes `frames` times into two targets in turn (the command buffers' ring wraps),
  /// and reads the last.
  /// `shared`: both views are rectangles of one image (outer's), as in an app with one
  /// swapchain for all views.
  std::vector<std::uint8_t> compose_vk(int frames, const View& outer_view, const View& inner_view, bool shared = false) {
    const VkImage outer =
        vulkan_->image(outer_view.image_w, outer_view.image_h, VK_FORMAT_R8G8B8A8_SRGB, outer_view.rgba.data());
    const VkImage inner = shared ? outer
                                 : vulkan_->image(inner_view.image_w, inner_view.image_h, VK_FORMAT_R8G8B8A8_SRGB,
                                                  inner_view.rgba.data());
    EXPECT_TRUE(outer && inner);
    return compose_vk(frames, vk_source(outer_view, outer, 1), vk_source(inner_view, inner, shared ? 1 : 2));
  }
  std::vector<std::uint8_t> compose_vk(int frames, const ComposeSource& outer, const ComposeSource& inner) {
    const VkImage targets[2] = {vulkan_->image(kW, kH, VK_FORMAT_R8G8B8A8_SRGB, nullptr),
                                vulkan_->image(kW, kH, VK_FORMAT_R8G8B8A8_SRGB, nullptr)};
    EXPECT_TRUE(targets[0] && targets[1]);
    ComposeTarget t{};
    for (int f = 0; f < frames; ++f) {
      t = {reinterpret_cast<std::uint64_t>(targets[f % 2]), VK_FORMAT_R8G8B8A8_SRGB, 10u + static_cast<unsigned>(f % 2),
           kW, kH};
      EXPECT_TRUE(vk_composer_->compose(outer, inner, t, kOut, kBandDeg)) << "frame " << f;
    }
    std::vector<std::uint8_t> rgba;
    EXPECT_TRUE(vk_composer_->read(t, rgba));
    return rgba;
  }

  std::unique_ptr<gl::EglContext> egl_;
  std::unique_ptr<VkHeadless> vulkan_;
  std::unique_ptr<GlComposer> gl_composer_;
  std::unique_ptr<VkComposer> vk_composer_;
  View outer_, inner_;
};

// Tolerances: lavapipe against llvmpipe gave max |diff| 1 (PSNR 80 dB), each against the
// double-precision reference max 1 (58.7 dB): 8-bit bilinear weights and sRGB rounding. A
// misplaced view, a hard edge or a missing inset costs tens of levels on noise.
constexpr int kMaxAbsGlVk = 2;
constexpr double kMinPsnrGlVk = 60.0;
constexpr int kMaxAbsReference = 3;
constexpr double kMinPsnrReference = 50.0;

TEST_F(VkComposerTest, VulkanGivesTheGlImageAndBothFollowTheMath) {
  const std::vector<std::uint8_t> gl = compose_gl();
  const std::vector<std::uint8_t> vk = compose_vk(6, outer_, inner_);
  ASSERT_EQ(gl.size(), vk.size());
  const Diff gl_vk = compare(gl, vk);
  std::printf("Vulkan (%s) against GL: max |diff| %d, PSNR %.1f dB\n", vulkan_->device_name().c_str(), gl_vk.max_abs,
              gl_vk.psnr);
  EXPECT_LE(gl_vk.max_abs, kMaxAbsGlVk);
  EXPECT_GE(gl_vk.psnr, kMinPsnrGlVk);
  // Shared math could be shared wrong: both against compose.glsl's math on the CPU.
  const std::vector<std::uint8_t> ref = reference(outer_, inner_);
  const Diff gl_ref = compare(gl, ref), vk_ref = compare(vk, ref);
  std::printf("against the CPU reference: GL PSNR %.1f dB (max %d), Vulkan %.1f dB (max %d)\n", gl_ref.psnr,
              gl_ref.max_abs, vk_ref.psnr, vk_ref.max_abs);
  EXPECT_GE(gl_ref.psnr, kMinPsnrReference);
  EXPECT_GE(vk_ref.psnr, kMinPsnrReference);
  EXPECT_LE(gl_ref.max_abs, kMaxAbsReference);
  EXPECT_LE(vk_ref.max_abs, kMaxAbsReference);
}

TEST_F(VkComposerTest, InsideTheBandTheInnerViewIsShownAtFullDensity) {
  const std::vector<std::uint8_t> vk = compose_vk(1, outer_, inner_);
  const std::vector<std::uint8_t> gl = compose_gl();
  // Pixels more than the band plus two pixels' angle inside the inner view's edge.
  const double inside = kBandDeg * M_PI / 180.0 + 2 * 0.00625;
  int checked = 0, worst_vk = 0, worst_gl = 0;
  for (int row = 0; row < kH; ++row)
    for (int col = 0; col < kW; ++col) {
      const double tx = kOut.left + (col + 0.5) * 0.00625, ty = kOut.up - (row + 0.5) * 0.00625;
      if (edge_angle(tx, ty) <= inside) continue;
      // The inner view's texel under this pixel: column 176, row 64 is its corner.
      const std::size_t texel =
          static_cast<std::size_t>(((inner_.y + row - 64) * inner_.image_w + inner_.x + col - 176) * 4);
      const std::size_t pixel = static_cast<std::size_t>((row * kW + col) * 4);
      for (int c = 0; c < 4; ++c) {
        worst_vk = std::max(worst_vk, std::abs(int(vk[pixel + c]) - int(inner_.rgba[texel + c])));
        worst_gl = std::max(worst_gl, std::abs(int(gl[pixel + c]) - int(inner_.rgba[texel + c])));
      }
      ++checked;
    }
  EXPECT_GT(checked, 3000);  // most of the 112×96 inset
  EXPECT_LE(worst_vk, 1) << "the Vulkan composer's inset is not the inner view's image";
  EXPECT_LE(worst_gl, 1) << "the GL composer's inset is not the inner view's image";
}

TEST_F(VkComposerTest, OuterAndInnerViewsInOneImageComposeAsWell) {
  // One 308×140 image: the outer view's image on the left, the inner view's on its right.
  View atlas_outer = outer_, atlas_inner = inner_;
  const int w = outer_.image_w + inner_.image_w, h = std::max(outer_.image_h, inner_.image_h);
  std::vector<std::uint8_t> atlas(static_cast<std::size_t>(w * h * 4), 0);
  for (int y = 0; y < h; ++y) {
    if (y < outer_.image_h)
      std::copy_n(&outer_.rgba[static_cast<std::size_t>(y * outer_.image_w * 4)], outer_.image_w * 4,
                  &atlas[static_cast<std::size_t>(y * w * 4)]);
    if (y < inner_.image_h)
      std::copy_n(&inner_.rgba[static_cast<std::size_t>(y * inner_.image_w * 4)], inner_.image_w * 4,
                  &atlas[static_cast<std::size_t>((y * w + outer_.image_w) * 4)]);
  }
  for (View* v : {&atlas_outer, &atlas_inner}) v->image_w = w, v->image_h = h, v->rgba = atlas;
  atlas_inner.x += outer_.image_w;
  const std::vector<std::uint8_t> vk = compose_vk(3, atlas_outer, atlas_inner, true);
  const Diff d = compare(vk, reference(outer_, inner_));
  std::printf("one image for both views, against the CPU reference: PSNR %.1f dB (max %d)\n", d.psnr, d.max_abs);
  EXPECT_GE(d.psnr, kMinPsnrReference);
  EXPECT_LE(d.max_abs, kMaxAbsReference);
}

TEST_F(VkComposerTest, ViewsInLayersOfOneArrayImageComposeOnBothApis) {
  // One 200×150 image of four layers, as an app with one swapchain of arraySize 4 for all
  // views: the outer view in layer 1, the inner view in layer 3, each at its own place;
  // layers 0 and 2 (the other eye's views) and the rest are other noise, so that a wrong
  // layer or a wrong rectangle shows.
  ArrayImage a = noise_array(200, 150, 4, 7);
  const View outer = put_in_layer(a, 1, 12, 5, outer_), inner = put_in_layer(a, 3, 40, 30, inner_);
  const std::vector<std::uint8_t> ref = reference(outer_, inner_);

  const GLuint array = gl_array_texture(a), plain_outer = gl_texture(outer_), plain_inner = gl_texture(inner_);
  const std::vector<std::uint8_t> gl =
      compose_gl(in_layer(gl_source(outer, array), 1), in_layer(gl_source(inner, array), 3));
  // One view in an array and the other in a plain image (each sampler type alone).
  const std::vector<std::uint8_t> gl_inner_array =
      compose_gl(gl_source(outer_, plain_outer), in_layer(gl_source(inner, array), 3));
  const std::vector<std::uint8_t> gl_outer_array =
      compose_gl(in_layer(gl_source(outer, array), 1), gl_source(inner_, plain_inner));
  const GLuint all[3] = {array, plain_outer, plain_inner};
  glDeleteTextures(3, all);

  const VkImage image = vulkan_->image(a.w, a.h, VK_FORMAT_R8G8B8A8_SRGB, a.rgba.data(), a.layers);
  ASSERT_TRUE(image);
  const std::vector<std::uint8_t> vk =
      compose_vk(6, in_layer(vk_source(outer, image, 5), 1), in_layer(vk_source(inner, image, 5), 3));

  const struct {
    const char* what;
    const std::vector<std::uint8_t>& rgba;
  } cases[] = {{"GL, both views in layers", gl},
               {"GL, the inner view in a layer", gl_inner_array},
               {"GL, the outer view in a layer", gl_outer_array},
               {"Vulkan, both views in layers", vk}};
  for (const auto& c : cases) {
    ASSERT_EQ(c.rgba.size(), ref.size()) << c.what;
    const Diff d = compare(c.rgba, ref);
    std::printf("array image, %s, against the CPU reference: PSNR %.1f dB (max %d)\n", c.what, d.psnr, d.max_abs);
    EXPECT_GE(d.psnr, kMinPsnrReference) << c.what;
    EXPECT_LE(d.max_abs, kMaxAbsReference) << c.what;
  }
  const Diff gl_vk = compare(gl, vk);
  std::printf("array image: Vulkan against GL: max |diff| %d, PSNR %.1f dB\n", gl_vk.max_abs, gl_vk.psnr);
  EXPECT_LE(gl_vk.max_abs, kMaxAbsGlVk);
  EXPECT_GE(gl_vk.psnr, kMinPsnrGlVk);
}

}  // namespace
}  // namespace foveal::openxr

// foveal-rmfr on real GL: the mapping pass copies every attachment kind from the source
// pixel the C++ mapping names, the lighting-shader GLSL finds the same pixel, σ = 1
// resolves to the input, and bad arguments are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "foveal/render/gl_objects.hpp"
#include "foveal/rmfr.hpp"
#include "foveal/rmfr_mapping.hpp"
#include "gl_support.hpp"

using namespace foveal;

namespace {

constexpr int kW = 97, kH = 61;  // odd sizes: no accidental symmetry

gl::Texture texture(GLenum format, int w, int h) { return gl::make_texture_2d(format, w, h); }

// A G-buffer whose texels name their pixel: RG32UI (x, y), R32I (-x - 1000 y),
// RGBA8 (x, y, 7, 255), depth (x + y·W) / (W·H).
struct Source {
  gl::Texture xy = texture(GL_RG32UI, kW, kH), neg = texture(GL_R32I, kW, kH), rgba = texture(GL_RGBA8, kW, kH),
              depth = texture(GL_DEPTH_COMPONENT32F, kW, kH);
  Source() {
    std::vector<std::uint32_t> xy_px;
    std::vector<std::int32_t> neg_px;
    std::vector<std::uint8_t> rgba_px;
    std::vector<float> depth_px;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        xy_px.insert(xy_px.end(), {std::uint32_t(x), std::uint32_t(y)});
        neg_px.push_back(-x - 1000 * y);
        rgba_px.insert(rgba_px.end(), {std::uint8_t(x), std::uint8_t(y), 7, 255});
        depth_px.push_back(float(x + y * kW) / float(kW * kH));
      }
    glTextureSubImage2D(xy.id(), 0, 0, 0, kW, kH, GL_RG_INTEGER, GL_UNSIGNED_INT, xy_px.data());
    glTextureSubImage2D(neg.id(), 0, 0, 0, kW, kH, GL_RED_INTEGER, GL_INT, neg_px.data());
    glTextureSubImage2D(rgba.id(), 0, 0, 0, kW, kH, GL_RGBA, GL_UNSIGNED_BYTE, rgba_px.data());
    glTextureSubImage2D(depth.id(), 0, 0, 0, kW, kH, GL_DEPTH_COMPONENT, GL_FLOAT, depth_px.data());
  }
  std::vector<unsigned> names() const { return {xy.id(), neg.id(), rgba.id(), depth.id()}; }
  std::vector<unsigned> formats() const { return {GL_RG32UI, GL_R32I, GL_RGBA8, GL_DEPTH_COMPONENT32F}; }
};

template <class T>
std::vector<T> read(GLuint tex, GLenum format, GLenum type, int channels, int w, int h) {
  std::vector<T> v(static_cast<std::size_t>(w * h * channels));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(tex, 0, format, type, static_cast<GLsizei>(v.size() * sizeof(T)), v.data());
  return v;
}

rmfr::Plan plan(double sigma, double x, double y) {
  rmfr::EyeParams e;
  e.width = kW, e.height = kH, e.sigma = sigma, e.fovea = {x, y}, e.fx = 0.2, e.fy = 0.35;
  auto p = rmfr::plan_eye(e);
  EXPECT_TRUE(p);
  return *p;
}

// The pixel the C++ mapping gives texel (i, j) (GL frame, as the shaders).
std::pair<int, int> expected_source(const rmfr::Plan& p, int i, int j) {
  return {rmfr::rmfr_source_pixel(i, p.buffer_w, p.screen_w, p.fovea_x, p.fx),
          rmfr::rmfr_source_pixel(j, p.buffer_h, p.screen_h, p.fovea_y, p.fy)};
}

}  // namespace

TEST(RmfrFoveator, MapCopiesEveryAttachmentKindFromTheCppSourcePixel) {
  ASSERT_TRUE(test::gl_ready());
  auto fov = rmfr::Foveator::create();
  ASSERT_TRUE(fov) << fov.error().message;
  const Source src;
  for (const auto& [sigma, x, y] : {std::tuple{2.6, 0.3, 0.8}, std::tuple{1.7, 0.0, 1.0}, std::tuple{3.0, 1.0, 0.5}}) {
    const rmfr::Plan p = plan(sigma, x, y);
    auto buffers = rmfr::EyeBuffers::create(p.buffer_w, p.buffer_h, src.formats(), GL_RGBA16F);
    ASSERT_TRUE(buffers) << buffers.error().message;
    ASSERT_TRUE(fov->map(p, src.names(), buffers->gbuffer_framebuffer()));
    glFinish();
    const int w = p.buffer_w, h = p.buffer_h;
    const auto xy = read<std::uint32_t>(buffers->gbuffer_texture(0), GL_RG_INTEGER, GL_UNSIGNED_INT, 2, w, h);
    const auto neg = read<std::int32_t>(buffers->gbuffer_texture(1), GL_RED_INTEGER, GL_INT, 1, w, h);
    const auto rgba = read<std::uint8_t>(buffers->gbuffer_texture(2), GL_RGBA, GL_UNSIGNED_BYTE, 4, w, h);
    const auto depth = read<float>(buffers->gbuffer_texture(3), GL_RED, GL_FLOAT, 1, w, h);
    int exact = 0, off_by_one = 0;
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        const std::size_t k = static_cast<std::size_t>(j * w + i);
        const int gx = int(xy[2 * k]), gy = int(xy[2 * k + 1]);
        // Every attachment holds the same pixel.
        ASSERT_EQ(neg[k], -gx - 1000 * gy);
        ASSERT_EQ(rgba[4 * k], gx);
        ASSERT_EQ(rgba[4 * k + 1], gy);
        ASSERT_EQ(depth[k], float(gx + gy * kW) / float(kW * kH));
        const auto [ex, ey] = expected_source(p, i, j);
        if (gx == ex && gy == ey) ++exact;
        else if (std::abs(gx - ex) <= 1 && std::abs(gy - ey) <= 1) ++off_by_one;  // float vs double at a pixel edge
        else ADD_FAILURE() << "texel " << i << "," << j << ": pixel " << gx << "," << gy << ", C++ says " << ex << "," << ey;
      }
    EXPECT_GE(exact, w * h - 2) << "sigma " << sigma << ": " << off_by_one << " texels one pixel off";
  }
}

TEST(RmfrFoveator, LightingShaderGlslFindsTheMappedPixelAndEccentricity) {
  ASSERT_TRUE(test::gl_ready());
  auto fov = rmfr::Foveator::create();
  ASSERT_TRUE(fov);
  const Source src;
  const rmfr::Plan p = plan(2.2, 0.7, 0.2);
  auto buffers = rmfr::EyeBuffers::create(p.buffer_w, p.buffer_h, src.formats(), GL_RGBA32F);
  ASSERT_TRUE(buffers);
  ASSERT_TRUE(fov->map(p, src.names(), buffers->gbuffer_framebuffer()));
  // An application's "lighting" shader: writes the screen pixel and eccentricity the GLSL gives.
  const std::string vs = "#version 450 core\nvoid main() { vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2); gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0); }\n";
  const std::string fs = "#version 450 core\n" + std::string(rmfr::glsl_source()) +
                         "out vec4 o;\nvoid main() { ivec2 t = ivec2(gl_FragCoord.xy); o = vec4(vec2(foveal_rmfr_screen_pixel(t)), "
                         "foveal_rmfr_eccentricity_deg(t), foveal_rmfr_footprint(t).x); }\n";
  gl::Program prog = gl::Program::create();
  for (const auto& [type, text] : {std::pair{GL_VERTEX_SHADER, &vs}, std::pair{GL_FRAGMENT_SHADER, &fs}}) {
    GLuint s = glCreateShader(type);
    const char* c = text->c_str();
    glShaderSource(s, 1, &c, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    char log[2048] = {};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    ASSERT_TRUE(ok) << log;
    glAttachShader(prog.id(), s);
    glDeleteShader(s);
  }
  glLinkProgram(prog.id());
  rmfr::set_uniforms(prog.id(), p);
  gl::VertexArray vao = gl::VertexArray::create();
  glBindFramebuffer(GL_FRAMEBUFFER, buffers->lit_framebuffer());
  glViewport(0, 0, p.buffer_w, p.buffer_h);
  glDisable(GL_FRAMEBUFFER_SRGB);
  glUseProgram(prog.id());
  glBindVertexArray(vao.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glFinish();
  const auto lit = read<float>(buffers->lit_texture(), GL_RGBA, GL_FLOAT, 4, p.buffer_w, p.buffer_h);
  const auto xy = read<std::uint32_t>(buffers->gbuffer_texture(0), GL_RG_INTEGER, GL_UNSIGNED_INT, 2, p.buffer_w, p.buffer_h);
  const double fovea_px_x = p.fovea_x * kW, fovea_px_y = p.fovea_y * kH;  // the frustum is ±1: f = W/2, H/2 per axis
  for (int k = 0; k < p.buffer_w * p.buffer_h; ++k) {
    const std::size_t i = static_cast<std::size_t>(k);
    ASSERT_EQ(lit[4 * i], float(xy[2 * i])) << k;
    ASSERT_EQ(lit[4 * i + 1], float(xy[2 * i + 1])) << k;
    const double tx = (xy[2 * i] + 0.5) / kW * 2 - 1, ty = (xy[2 * i + 1] + 0.5) / kH * 2 - 1;
    const double gx = fovea_px_x / kW * 2 - 1, gy = fovea_px_y / kH * 2 - 1;
    const double c = (tx * gx + ty * gy + 1) / std::sqrt((tx * tx + ty * ty + 1) * (gx * gx + gy * gy + 1));
    ASSERT_NEAR(lit[4 * i + 2], std::acos(std::min(c, 1.0)) * 180 / M_PI, 0.05) << k;
    ASSERT_GT(lit[4 * i + 3], 0.0f);
  }
}

TEST(RmfrFoveator, SigmaOneResolvesToTheInputAndTheLensBlackensTheCorners) {
  ASSERT_TRUE(test::gl_ready());
  auto fov = rmfr::Foveator::create();
  ASSERT_TRUE(fov);
  const rmfr::Plan p = plan(1.0, 0.2, 0.9);
  gl::Texture lit = texture(GL_RGBA8, kW, kH), out = texture(GL_RGBA8, 2 * kW, kH);
  std::vector<std::uint8_t> px;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) px.insert(px.end(), {std::uint8_t(x * 2), std::uint8_t(y * 4), std::uint8_t((x * y) % 251), 255});
  glTextureSubImage2D(lit.id(), 0, 0, 0, kW, kH, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
  gl::Framebuffer fbo = gl::Framebuffer::create();
  glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, out.id(), 0);
  glNamedFramebufferDrawBuffer(fbo.id(), GL_COLOR_ATTACHMENT0);
  ASSERT_TRUE(fov->resolve(p, lit.id(), fbo.id(), kW, 0));  // the right half
  const auto img = read<std::uint8_t>(out.id(), GL_RGBA, GL_UNSIGNED_BYTE, 4, 2 * kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 4; ++c)
        ASSERT_EQ(img[static_cast<std::size_t>((y * 2 * kW + kW + x) * 4 + c)], px[static_cast<std::size_t>((y * kW + x) * 4 + c)])
            << x << "," << y;
  rmfr::Lens lens;
  lens.k1 = 0.5;
  ASSERT_TRUE(fov->resolve(p, lit.id(), fbo.id(), 0, 0, &lens));
  const auto bent = read<std::uint8_t>(out.id(), GL_RGBA, GL_UNSIGNED_BYTE, 4, 2 * kW, kH);
  EXPECT_EQ(bent[0] + bent[1] + bent[2], 0);  // a corner samples outside the image
  const std::size_t centre = static_cast<std::size_t>(((kH / 2) * 2 * kW + kW / 2) * 4);
  EXPECT_EQ(bent[centre], px[static_cast<std::size_t>(((kH / 2) * kW + kW / 2) * 4)]);
}

TEST(RmfrFoveator, BadArgumentsAreRefusedNamingWhat) {
  ASSERT_TRUE(test::gl_ready());
  auto fov = rmfr::Foveator::create();
  ASSERT_TRUE(fov);
  const Source src;
  const rmfr::Plan p = plan(2.0, 0.5, 0.5);
  auto buffers = rmfr::EyeBuffers::create(p.buffer_w, p.buffer_h, src.formats(), GL_RGBA8);
  ASSERT_TRUE(buffers);
  const GLuint dst = buffers->gbuffer_framebuffer();
  auto message = [](const Status& s) { return s ? std::string("ok") : s.error().message; };
  EXPECT_NE(message(fov->map(p, {}, dst)).find("0 G-buffer textures"), std::string::npos);
  const std::vector<unsigned> not_texture = {src.xy.id(), 987654};
  EXPECT_NE(message(fov->map(p, not_texture, dst)).find("is no texture"), std::string::npos);
  const gl::Texture small = texture(GL_RG32UI, 10, 10);
  const std::vector<unsigned> too_small = {small.id()};
  EXPECT_NE(message(fov->map(p, too_small, dst)).find("smaller than the eye's"), std::string::npos);
  const std::vector<unsigned> swapped = {src.rgba.id()};  // float source into the RG32UI attachment
  EXPECT_NE(message(fov->map(p, swapped, dst)).find("does not match"), std::string::npos);
  EXPECT_NE(message(fov->map(p, src.names(), 0)).find("default framebuffer"), std::string::npos);
  EXPECT_NE(message(fov->resolve(p, small.id(), 0, 0, 0)).find("smaller than the buffer"), std::string::npos);
  EXPECT_FALSE(rmfr::EyeBuffers::create(0, 5, src.formats(), GL_RGBA8));
  const std::vector<unsigned> stencil = {GL_STENCIL_INDEX8};
  EXPECT_FALSE(rmfr::EyeBuffers::create(5, 5, stencil, GL_RGBA8));
  const std::vector<unsigned> nonsense = {0x1234};
  auto refused = rmfr::EyeBuffers::create(5, 5, nonsense, GL_RGBA8);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().kind, ErrorKind::unsupported);
  while (glGetError() != GL_NO_ERROR) {}  // the refused format's GL_INVALID_ENUM
}

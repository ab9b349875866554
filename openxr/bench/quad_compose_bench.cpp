// What the layer's quad-view composition costs and buys, per frame at a display's size
// (default 2880x1600, the Vive Pro Eye): the composer's time for both eyes (GPU time
// from timer queries, and wall time to glFinish), the Vulkan composer's (wall time to its
// fences, on the first CPU device or else the first device) where built with Vulkan, and
// the pixels an app shades with quad views against stereo, for the profile's EFR pair.
// docs/openxr.md, "Quad views".
//
//   foveal_quad_compose_bench [--size WxH] [--sigma-d S] [--sigma-nd S] [--inset SHARE]
//                             [--frames N] [--json]
#include <EGL/egl.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "foveal/render/egl_context.hpp"
#include "foveal/render/gl.hpp"
#include "gl_composer.hpp"
#include "inset.hpp"
#ifdef FOVEAL_BENCH_VULKAN
#include "vk_headless.hpp"
#endif

namespace {

GLuint noise_texture(int w, int h, GLenum format, unsigned seed) {
  std::vector<std::uint8_t> px(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
  std::mt19937 rng(seed);
  for (auto& v : px) v = static_cast<std::uint8_t>(rng());
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, 1, format, w, h);
  glTextureSubImage2D(t, 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
  return t;
}

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1))];
}

#ifdef FOVEAL_BENCH_VULKAN
/// Both eyes' composition on Vulkan, wall time from the first submit to the fences; the
/// device's name in `device`; empty without a Vulkan device.
std::vector<double> vulkan_ms(const foveal::openxr::QuadSizes& q, const foveal::openxr::ComposeSource gl_src[4],
                              int eye_w, int height, int frames, std::string& device) {
  using namespace foveal::openxr;
  std::string error;
  auto vk = VkHeadless::create(error);
  auto composer = vk ? VkComposer::create(vk->binding(), error) : nullptr;
  if (!composer) {
    device = "none (" + error + ")";
    return {};
  }
  device = vk->device_name();
  ComposeSource src[4];
  for (int v = 0; v < 4; ++v) {
    const int w = static_cast<int>(q.width[v]), h = static_cast<int>(q.height[v]);
    std::vector<std::uint8_t> px(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
    std::mt19937 rng(7u + static_cast<unsigned>(v));
    for (auto& b : px) b = static_cast<std::uint8_t>(rng());
    src[v] = gl_src[v];
    src[v].image = reinterpret_cast<std::uint64_t>(vk->image(w, h, VK_FORMAT_R8G8B8A8_SRGB, px.data()));
    src[v].format = VK_FORMAT_R8G8B8A8_SRGB;
    src[v].serial = static_cast<std::uint64_t>(v) + 1;
  }
  ComposeTarget target[2];
  for (int e = 0; e < 2; ++e)
    target[e] = {reinterpret_cast<std::uint64_t>(vk->image(eye_w, height, VK_FORMAT_R8G8B8A8_SRGB, nullptr)),
                 VK_FORMAT_R8G8B8A8_SRGB, 10u + static_cast<std::uint64_t>(e), eye_w, height};
  std::vector<double> ms;
  for (int f = -3; f < frames; ++f) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int e = 0; e < 2; ++e) composer->compose(src[e], src[e + 2], target[e], gl_src[e].fov, 3.0f);
    composer->finish();
    if (f >= 0) ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  composer.reset();  // before its device
  return ms;
}
#endif

}  // namespace

int main(int argc, char** argv) {
  int width = 2880, height = 1600, frames = 100;
  double sigma_d = 2.0, sigma_nd = 3.0;
  float share = 0.35f;
  bool json = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> const char* {
      if (i + 1 >= argc) std::exit((std::fprintf(stderr, "%s needs a value\n", a.c_str()), 2));
      return argv[++i];
    };
    if (a == "--size") {
      if (std::sscanf(next(), "%dx%d", &width, &height) != 2 || width < 64 || height < 64 || width > 16384 || height > 16384)
        return std::fprintf(stderr, "--size: WxH, 64 to 16384 each\n"), 2;
    } else if (a == "--sigma-d") sigma_d = std::atof(next());
    else if (a == "--sigma-nd") sigma_nd = std::atof(next());
    else if (a == "--inset") share = static_cast<float>(std::atof(next()));
    else if (a == "--frames") frames = std::atoi(next());
    else if (a == "--json") json = true;
    else if (a == "--help" || a == "-h") {
      std::printf("usage: foveal_quad_compose_bench [--size WxH] [--sigma-d S] [--sigma-nd S] [--inset SHARE] [--frames N] [--json]\n"
                  "  Times the OpenXR layer's quad-view composition for both eyes at a side-by-side WxH\n"
                  "  (default 2880x1600) and counts the pixels an app shades, quad views against stereo.\n");
      return 0;
    } else return std::fprintf(stderr, "unknown option %s (try --help)\n", a.c_str()), 2;
  }
  if (!(sigma_d >= 1 && sigma_nd >= sigma_d && sigma_nd <= 16) || !(share > 0 && share <= 1) || frames < 1)
    return std::fprintf(stderr, "need 1 <= sigma-d <= sigma-nd <= 16, 0 < inset <= 1, frames >= 1\n"), 2;
  auto ctx = foveal::gl::EglContext::create();
  if (!ctx) return std::fprintf(stderr, "%s\n", ctx.error().message.c_str()), 1;
  std::string error;
  auto composer = foveal::openxr::GlComposer::create(
      [](const char* n) { return reinterpret_cast<void*>(eglGetProcAddress(n)); }, error);
  if (!composer) return std::fprintf(stderr, "%s\n", error.c_str()), 1;

  const int eye_w = width / 2;
  const std::uint32_t sw[2] = {static_cast<std::uint32_t>(eye_w), static_cast<std::uint32_t>(eye_w)};
  const std::uint32_t sh[2] = {static_cast<std::uint32_t>(height), static_cast<std::uint32_t>(height)};
  const float density[2] = {static_cast<float>(1.0 / sigma_nd), static_cast<float>(1.0 / sigma_d)};  // left non-dominant
  const foveal::openxr::QuadSizes q = foveal::openxr::quad_sizes(sw, sh, density, share, share);
  // The Vive Pro Eye's field, roughly (docs/display-model.md): about ±50° across.
  const foveal::openxr::TanRect outer{-1.19f, 1.19f, -1.19f, 1.19f};
  foveal::openxr::ComposeSource src[4];
  for (int v = 0; v < 4; ++v) {
    src[v].format = GL_SRGB8_ALPHA8;
    src[v].image = noise_texture(static_cast<int>(q.width[v]), static_cast<int>(q.height[v]), GL_SRGB8_ALPHA8, 7u + static_cast<unsigned>(v));
    src[v].image_w = src[v].w = static_cast<int>(q.width[v]);
    src[v].image_h = src[v].h = static_cast<int>(q.height[v]);
    src[v].fov = v < 2 ? outer : foveal::openxr::place_inset(outer, share, share, 0.2f, -0.1f);
  }
  GLuint target[2];
  for (auto& t : target) {
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, GL_SRGB8_ALPHA8, eye_w, height);
  }
  GLuint query = 0;
  glGenQueries(1, &query);
  std::vector<double> gpu_ms, wall_ms;
  for (int f = -3; f < frames; ++f) {  // three frames of warm-up
    const auto t0 = std::chrono::steady_clock::now();
    glBeginQuery(GL_TIME_ELAPSED, query);
    for (int e = 0; e < 2; ++e)
      composer->compose(src[e], src[e + 2], {target[e], GL_SRGB8_ALPHA8, 0, eye_w, height}, outer, 3.0f);
    glEndQuery(GL_TIME_ELAPSED);
    glFinish();
    const auto t1 = std::chrono::steady_clock::now();
    GLuint64 ns = 0;
    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
    if (f < 0) continue;
    gpu_ms.push_back(static_cast<double>(ns) / 1e6);
    wall_ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
  }
  double quad_px = 0;
  for (int v = 0; v < 4; ++v) quad_px += static_cast<double>(q.width[v]) * static_cast<double>(q.height[v]);
  const double stereo_px = 2.0 * eye_w * height;
  char renderer[160];
  std::snprintf(renderer, sizeof renderer, "%s", reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
  std::string vk_device = "not built";
  std::vector<double> vk_ms;
#ifdef FOVEAL_BENCH_VULKAN
  vk_ms = vulkan_ms(q, src, eye_w, height, frames, vk_device);
#endif
  const double vk_p50 = vk_ms.empty() ? -1 : percentile(vk_ms, 0.5), vk_p95 = vk_ms.empty() ? -1 : percentile(vk_ms, 0.95);
  if (json) {
    std::printf("{\"renderer\":\"%s\",\"size\":[%d,%d],\"sigma_d\":%g,\"sigma_nd\":%g,\"inset\":%g,\"frames\":%d,"
                "\"compose_gpu_ms\":{\"p50\":%.3f,\"p95\":%.3f},\"compose_wall_ms\":{\"p50\":%.3f,\"p95\":%.3f},"
                "\"vulkan_device\":\"%s\",\"compose_vulkan_wall_ms\":{\"p50\":%.3f,\"p95\":%.3f},"
                "\"pixels\":{\"quad\":%.0f,\"stereo\":%.0f,\"ratio\":%.4f}}\n",
                renderer, width, height, sigma_d, sigma_nd, share, frames, percentile(gpu_ms, 0.5), percentile(gpu_ms, 0.95),
                percentile(wall_ms, 0.5), percentile(wall_ms, 0.95), vk_device.c_str(), vk_p50, vk_p95, quad_px, stereo_px,
                quad_px / stereo_px);
  } else {
    std::printf("renderer: %s\nsize %dx%d, σ_d %g (right), σ_nd %g (left), inset %.2f of the view\n", renderer, width, height,
                sigma_d, sigma_nd, share);
    std::printf("composition, both eyes: GPU p50 %.3f ms, p95 %.3f ms; wall to glFinish p50 %.3f ms (%d frames)\n",
                percentile(gpu_ms, 0.5), percentile(gpu_ms, 0.95), percentile(wall_ms, 0.5), frames);
    if (vk_ms.empty())
      std::printf("Vulkan composition: no Vulkan device (%s)\n", vk_device.c_str());
    else
      std::printf("Vulkan composition on %s, both eyes: wall to the fences p50 %.3f ms, p95 %.3f ms\n",
                  vk_device.c_str(), vk_p50, vk_p95);
    std::printf("pixels shaded by the app: quad %.0f, stereo %.0f: %.3f of stereo (%.2fx fewer)\n", quad_px, stereo_px,
                quad_px / stereo_px, stereo_px / quad_px);
  }
  return 0;
}

// vm_drm_probe: the KMS + GBM + EGL stack of direct mode without foveald, run by
// run_drm_vm_test.py in foveald's place (test vm_drm_probe, docs/vm-tests.md).
// With --drm it opens the card, picks the connected connector's WxH mode, creates EGL
// (OpenGL 4.5 core) on a GBM surface, draws a fixed test pattern and presents it with
// page flips until SIGTERM/SIGINT (or --frames N), writing OUT/frames.csv (one flushed
// row per presented frame, with the flip event's sequence and timestamp) and
// OUT/summary.json. Without --drm it draws the same pattern headless (surfaceless EGL,
// an FBO) and saves OUT/frame_NNNNNN.png of the last of --frames frames, as foveald
// saves its frames, for the test to compare the screen with.
#define GL_GLEXT_PROTOTYPES 1
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>
#include <fcntl.h>
#include <gbm.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>
#include <xf86drm.h>
#include <xf86drmMode.h>
#include <zlib.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

namespace {

volatile sig_atomic_t g_stop = 0;

std::int64_t now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return std::int64_t(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

double ms(std::int64_t ns) { return static_cast<double>(ns) / 1e6; }

[[noreturn]] void die(const char* what) {
  std::fprintf(stderr, "vm_drm_probe: %s (errno %d %s, EGL 0x%04x)\n", what, errno, std::strerror(errno), eglGetError());
  std::exit(1);
}

// A pattern whose every region is easy to tell apart: 64 px checks, red top half, blue
// bottom half (catches a vertical flip), a green ramp from left to right.
const char* kVertex = R"(#version 450 core
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
})";
const char* kFragment = R"(#version 450 core
uniform vec2 size;
out vec4 color;
void main() {
  ivec2 c = ivec2(gl_FragCoord.xy) / 64;
  float check = ((c.x + c.y) & 1) == 0 ? 1.0 : 0.5;
  bool top = gl_FragCoord.y >= size.y * 0.5;  // GL's y grows upwards
  color = vec4(top ? check : 0.0, gl_FragCoord.x / size.x, top ? 0.0 : check, 1.0);
})";

GLuint program() {
  auto compile = [](GLenum type, const char* src) {
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) die("shader compile");
    return s;
  };
  GLuint p = glCreateProgram();
  glAttachShader(p, compile(GL_VERTEX_SHADER, kVertex));
  glAttachShader(p, compile(GL_FRAGMENT_SHADER, kFragment));
  glLinkProgram(p);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) die("program link");
  return p;
}

void draw(GLuint prog, GLuint vao, int w, int h) {
  glViewport(0, 0, w, h);
  glUseProgram(prog);
  glUniform2f(glGetUniformLocation(prog, "size"), float(w), float(h));
  glBindVertexArray(vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

EGLContext make_context(EGLDisplay dpy, EGLConfig cfg) {
  if (!eglBindAPI(EGL_OPENGL_API)) die("eglBindAPI");
  const EGLint attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                          EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext ctx = eglCreateContext(dpy, cfg, EGL_NO_CONTEXT, attrs);
  if (ctx == EGL_NO_CONTEXT) die("eglCreateContext 4.5 core");
  return ctx;
}

void print_gl() {
  std::printf("vm_drm_probe: GL %s / %s / %s\n", glGetString(GL_VENDOR), glGetString(GL_RENDERER), glGetString(GL_VERSION));
}

// RGBA rows bottom-up (glReadPixels) -> an 8-bit RGB PNG, top row first.
void save_png(const std::string& path, const std::vector<std::uint8_t>& rgba, int w, int h) {
  std::vector<std::uint8_t> raw;
  raw.reserve(std::size_t(h) * (1 + 3 * w));
  for (int y = h - 1; y >= 0; --y) {
    raw.push_back(0);  // filter: none
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) raw.push_back(rgba[(std::size_t(y) * w + x) * 4 + c]);
  }
  uLongf zlen = compressBound(raw.size());
  std::vector<std::uint8_t> z(zlen);
  if (compress2(z.data(), &zlen, raw.data(), raw.size(), 1) != Z_OK) die("compress");
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) die("open png");
  auto chunk = [f](const char* type, const std::uint8_t* data, std::uint32_t n) {
    const std::uint8_t len[4] = {std::uint8_t(n >> 24), std::uint8_t(n >> 16), std::uint8_t(n >> 8), std::uint8_t(n)};
    std::fwrite(len, 1, 4, f);
    std::fwrite(type, 1, 4, f);
    std::fwrite(data, 1, n, f);
    uLong crc = crc32(crc32(0, reinterpret_cast<const Bytef*>(type), 4), data, n);
    const std::uint8_t c[4] = {std::uint8_t(crc >> 24), std::uint8_t(crc >> 16), std::uint8_t(crc >> 8), std::uint8_t(crc)};
    std::fwrite(c, 1, 4, f);
  };
  std::fwrite("\x89PNG\r\n\x1a\n", 1, 8, f);
  const std::uint8_t ihdr[13] = {std::uint8_t(w >> 24), std::uint8_t(w >> 16), std::uint8_t(w >> 8), std::uint8_t(w),
                                 std::uint8_t(h >> 24), std::uint8_t(h >> 16), std::uint8_t(h >> 8), std::uint8_t(h),
                                 8, 2, 0, 0, 0};
  chunk("IHDR", ihdr, 13);
  chunk("IDAT", z.data(), std::uint32_t(zlen));
  chunk("IEND", nullptr, 0);
  std::fclose(f);
}

int headless(const std::string& out, int w, int h, int frames) {
  auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  EGLDisplay dpy = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, nullptr, nullptr)) die("surfaceless EGL display");
  EGLContext ctx = make_context(dpy, EGL_NO_CONFIG_KHR);
  if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) die("eglMakeCurrent");
  print_gl();
  GLuint rb = 0, fbo = 0, vao = 0;
  glGenRenderbuffers(1, &rb);
  glBindRenderbuffer(GL_RENDERBUFFER, rb);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
  glGenFramebuffers(1, &fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
  glGenVertexArrays(1, &vao);
  const GLuint prog = program();
  for (int i = 0; i < frames; ++i) draw(prog, vao, w, h);
  std::vector<std::uint8_t> rgba(std::size_t(w) * h * 4);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  char name[64];
  std::snprintf(name, sizeof name, "/frame_%06d.png", frames - 1);
  save_png(out + name, rgba, w, h);
  std::printf("vm_drm_probe: headless %dx%d, %d frames -> %s%s\n", w, h, frames, out.c_str(), name);
  return 0;
}

struct Flip {
  bool done = false;
  unsigned sequence = 0;
  std::int64_t event_ns = 0;  // the event's timestamp (CLOCK_MONOTONIC with DRM_CAP_TIMESTAMP_MONOTONIC)
};

void on_flip(int, unsigned sequence, unsigned sec, unsigned usec, void* data) {
  auto* f = static_cast<Flip*>(data);
  f->done = true;
  f->sequence = sequence;
  f->event_ns = std::int64_t(sec) * 1000000000 + std::int64_t(usec) * 1000;
}

std::uint32_t fb_for(int fd, gbm_bo* bo) {
  if (void* id = gbm_bo_get_user_data(bo)) return std::uint32_t(reinterpret_cast<std::uintptr_t>(id));
  const std::uint32_t handles[4] = {gbm_bo_get_handle(bo).u32}, pitches[4] = {gbm_bo_get_stride(bo)}, offsets[4] = {0};
  std::uint32_t fb = 0;
  if (drmModeAddFB2(fd, gbm_bo_get_width(bo), gbm_bo_get_height(bo), gbm_bo_get_format(bo), handles, pitches, offsets,
                    &fb, 0))
    die("drmModeAddFB2");
  gbm_bo_set_user_data(bo, reinterpret_cast<void*>(std::uintptr_t(fb)), nullptr);
  return fb;
}

int direct(const char* card, const std::string& out, int w, int h, int max_frames) {
  const std::int64_t t0 = now_ns();
  const int fd = open(card, O_RDWR | O_CLOEXEC);
  if (fd < 0) die(card);
  if (drmVersion* v = drmGetVersion(fd)) {
    std::printf("vm_drm_probe: %s: driver %s (%s)\n", card, v->name, v->desc);
    drmFreeVersion(v);
  }
  std::uint64_t cap = 0;
  drmGetCap(fd, DRM_CAP_TIMESTAMP_MONOTONIC, &cap);
  std::printf("vm_drm_probe: DRM_CAP_TIMESTAMP_MONOTONIC %llu\n", static_cast<unsigned long long>(cap));
  drmModeRes* res = drmModeGetResources(fd);
  if (!res) die("drmModeGetResources");
  drmModeConnector* conn = nullptr;
  for (int i = 0; i < res->count_connectors && !conn; ++i) {
    drmModeConnector* c = drmModeGetConnector(fd, res->connectors[i]);
    if (c && c->connection == DRM_MODE_CONNECTED && c->count_modes > 0) conn = c;
    else drmModeFreeConnector(c);
  }
  if (!conn) die("no connected connector");
  // The connector's type and properties (an HMD's EDID quirk would set non-desktop).
  std::printf("vm_drm_probe: connector %u (%s-%u), properties:", conn->connector_id,
              drmModeGetConnectorTypeName(conn->connector_type), conn->connector_type_id);
  if (drmModeObjectProperties* props = drmModeObjectGetProperties(fd, conn->connector_id, DRM_MODE_OBJECT_CONNECTOR)) {
    for (std::uint32_t i = 0; i < props->count_props; ++i)
      if (drmModePropertyRes* pr = drmModeGetProperty(fd, props->props[i])) {
        std::printf(" %s=%llu", pr->name, static_cast<unsigned long long>(props->prop_values[i]));
        drmModeFreeProperty(pr);
      }
    drmModeFreeObjectProperties(props);
  }
  std::printf("\n");
  const drmModeModeInfo* mode = nullptr;
  std::printf("vm_drm_probe: %d modes:", conn->count_modes);
  for (int i = 0; i < conn->count_modes; ++i) {
    const drmModeModeInfo& m = conn->modes[i];
    std::printf(" %s@%u%s", m.name, m.vrefresh, m.type & DRM_MODE_TYPE_PREFERRED ? "(preferred)" : "");
    if (!mode && m.hdisplay == w && m.vdisplay == h) mode = &m;
  }
  std::printf("\n");
  if (!mode) die("no mode of the requested size");
  std::printf("vm_drm_probe: mode %s@%u clock %u kHz htotal %u vtotal %u -> %.3f Hz\n", mode->name, mode->vrefresh,
              mode->clock, mode->htotal, mode->vtotal, mode->clock * 1000.0 / (double(mode->htotal) * mode->vtotal));
  drmModeEncoder* enc = drmModeGetEncoder(fd, conn->encoder_id ? conn->encoder_id : conn->encoders[0]);
  const std::uint32_t crtc = enc && enc->crtc_id ? enc->crtc_id : res->crtcs[0];

  // vblank: does the driver count them at all (bochs has no vblank interrupt)?
  drmVBlank vbl{};
  vbl.request.type = DRM_VBLANK_RELATIVE;
  vbl.request.sequence = 0;
  const int vrc = drmWaitVBlank(fd, &vbl);
  std::printf("vm_drm_probe: drmWaitVBlank -> %d (%s)\n", vrc, vrc ? std::strerror(errno) : "ok");

  const std::int64_t t_mesa = now_ns();
  gbm_device* gbm = gbm_create_device(fd);
  if (!gbm) die("gbm_create_device");
  std::printf("vm_drm_probe: GBM backend %s\n", gbm_device_get_backend_name(gbm));
  gbm_surface* gs = gbm_surface_create(gbm, w, h, GBM_FORMAT_XRGB8888, GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
  if (!gs) die("gbm_surface_create");
  EGLDisplay dpy = eglGetPlatformDisplay(EGL_PLATFORM_GBM_KHR, gbm, nullptr);
  if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, nullptr, nullptr)) die("EGL on GBM");
  std::printf("vm_drm_probe: EGL %s %s\n", eglQueryString(dpy, EGL_VENDOR), eglQueryString(dpy, EGL_VERSION));
  // The config whose native visual is the surface's format.
  const EGLint cattrs[] = {EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_RED_SIZE, 8,
                           EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 0, EGL_NONE};
  EGLConfig cfgs[64];
  EGLint n = 0;
  eglChooseConfig(dpy, cattrs, cfgs, 64, &n);
  EGLConfig cfg = nullptr;
  for (EGLint i = 0; i < n && !cfg; ++i) {
    EGLint id = 0;
    eglGetConfigAttrib(dpy, cfgs[i], EGL_NATIVE_VISUAL_ID, &id);
    if (std::uint32_t(id) == GBM_FORMAT_XRGB8888) cfg = cfgs[i];
  }
  if (!cfg) die("no EGL config for XRGB8888");
  EGLContext ctx = make_context(dpy, cfg);
  EGLSurface surf = eglCreatePlatformWindowSurface(dpy, cfg, gs, nullptr);
  if (surf == EGL_NO_SURFACE) die("eglCreatePlatformWindowSurface");
  if (!eglMakeCurrent(dpy, surf, surf, ctx)) die("eglMakeCurrent");
  print_gl();
  GLuint vao = 0;
  glGenVertexArrays(1, &vao);
  const GLuint prog = program();
  std::printf("vm_drm_probe: open %.0f ms, Mesa init %.0f ms\n", ms(t_mesa - t0), ms(now_ns() - t_mesa));

  std::FILE* csv = std::fopen((out + "/frames.csv").c_str(), "w");
  if (!csv) die("frames.csv");
  std::fprintf(csv, "frame,t_ns,draw_swap_ms,flip_wait_ms,sequence,event_ns,event_minus_now_ms\n");
  std::fflush(csv);

  drmEventContext ev{};
  ev.version = 2;
  ev.page_flip_handler = on_flip;
  gbm_bo* shown = nullptr;
  double swap_sum = 0, wait_sum = 0;
  int frames = 0, events = 0;
  unsigned first_seq = 0, last_seq = 0;
  while (!g_stop && (max_frames == 0 || frames < max_frames)) {
    const std::int64_t t_draw = now_ns();
    draw(prog, vao, w, h);
    if (!eglSwapBuffers(dpy, surf)) die("eglSwapBuffers");
    gbm_bo* bo = gbm_surface_lock_front_buffer(gs);
    if (!bo) die("gbm_surface_lock_front_buffer");
    const std::uint32_t fb = fb_for(fd, bo);
    const std::int64_t t_flip = now_ns();
    Flip flip;
    if (!shown) {
      if (drmModeSetCrtc(fd, crtc, fb, 0, 0, &conn->connector_id, 1, const_cast<drmModeModeInfo*>(mode)))
        die("drmModeSetCrtc");
    } else {
      if (drmModePageFlip(fd, crtc, fb, DRM_MODE_PAGE_FLIP_EVENT, &flip)) die("drmModePageFlip");
      while (!flip.done && !g_stop) {
        pollfd p{fd, POLLIN, 0};
        if (poll(&p, 1, 1000) > 0) drmHandleEvent(fd, &ev);
      }
      if (!flip.done) break;  // stopped while waiting: the flip may still be pending
    }
    const std::int64_t t_done = now_ns();
    if (shown) gbm_surface_release_buffer(gs, shown);
    shown = bo;
    if (flip.done) {
      if (events++ == 0) first_seq = flip.sequence;
      last_seq = flip.sequence;
    }
    swap_sum += ms(t_flip - t_draw);
    wait_sum += ms(t_done - t_flip);
    std::fprintf(csv, "%d,%lld,%.3f,%.3f,%u,%lld,%.3f\n", frames, static_cast<long long>(t_done), ms(t_flip - t_draw),
                 ms(t_done - t_flip), flip.sequence, static_cast<long long>(flip.event_ns),
                 flip.done ? ms(flip.event_ns - t_done) : 0.0);
    std::fflush(csv);
    ++frames;
  }
  std::fclose(csv);
  std::FILE* sum = std::fopen((out + "/summary.json").c_str(), "w");
  if (!sum) die("summary.json");
  std::fprintf(sum,
               "{\"frames\": %d, \"flip_events\": %d, \"first_sequence\": %u, \"last_sequence\": %u, "
               "\"draw_swap_ms_mean\": %.1f, \"flip_wait_ms_mean\": %.1f, \"stopped_by_signal\": %s}\n",
               frames, events, first_seq, last_seq, frames ? swap_sum / frames : 0.0,
               events ? wait_sum / events : 0.0, g_stop ? "true" : "false");
  std::fclose(sum);
  std::printf("vm_drm_probe: %d frames presented, %d flip events\n", frames, events);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const char* card = nullptr;
  std::string out = "drm-probe-out";
  int w = 2880, h = 1600, frames = -1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc && argv[i + 1][0] != '-';
    if (a == "--drm") card = has_value ? argv[++i] : "/dev/dri/card0";
    else if ((a == "--out" || a == "-o") && has_value) out = argv[++i];
    else if (a == "--frames" && has_value) frames = std::atoi(argv[++i]);
    else if (a == "--size" && has_value && std::sscanf(argv[++i], "%dx%d", &w, &h) == 2) {}
    else {
      std::fprintf(stderr, "usage: vm_drm_probe [--drm [CARD]] [--out DIR] [--frames N] [--size WxH]\n");
      return 2;
    }
  }
  setvbuf(stdout, nullptr, _IOLBF, 0);
  struct sigaction sa{};
  sa.sa_handler = [](int) { g_stop = 1; };
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGINT, &sa, nullptr);
  mkdir(out.c_str(), 0755);
  if (card) return direct(card, out, w, h, frames < 0 ? 0 : frames);
  return headless(out, w, h, frames < 0 ? 3 : frames);
}

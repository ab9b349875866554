#include "foveal/render/drm_output.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <fcntl.h>
#include <gbm.h>
#include <poll.h>
#include <unistd.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>

#include "foveal/core/clock.hpp"
#include "foveal/render/egl_util.hpp"

namespace foveal::render {

namespace {

std::string errno_text(int e) { return std::strerror(e); }

// The refresh rate from the pixel clock: vrefresh is rounded (89.53 Hz reads 90).
double mode_refresh(const drmModeModeInfo& m) {
  if (m.htotal == 0 || m.vtotal == 0) return m.vrefresh;
  double hz = double(m.clock) * 1000.0 / (double(m.htotal) * double(m.vtotal));
  if (m.flags & DRM_MODE_FLAG_INTERLACE) hz *= 2;
  if (m.flags & DRM_MODE_FLAG_DBLSCAN) hz /= 2;
  if (m.vscan > 1) hz /= m.vscan;
  return hz;
}

struct Connector {
  KmsConnector info;
  std::vector<drmModeModeInfo> modes;  // parallel to info.modes
  std::vector<std::uint32_t> encoders;
  std::uint32_t encoder_id = 0;
};

Connector read_connector(int fd, drmModeConnector* c) {
  Connector out;
  const char* type = drmModeGetConnectorTypeName(c->connector_type);
  out.info.name = std::string(type ? type : "Unknown") + "-" + std::to_string(c->connector_type_id);
  out.info.id = c->connector_id;
  out.info.connected = c->connection == DRM_MODE_CONNECTED;
  for (int i = 0; i < c->count_modes; ++i) {
    const drmModeModeInfo& m = c->modes[i];
    out.modes.push_back(m);
    out.info.modes.push_back({m.hdisplay, m.vdisplay, mode_refresh(m), (m.type & DRM_MODE_TYPE_PREFERRED) != 0});
  }
  out.encoders.assign(c->encoders, c->encoders + c->count_encoders);
  out.encoder_id = c->encoder_id;
  if (drmModeObjectProperties* props = drmModeObjectGetProperties(fd, c->connector_id, DRM_MODE_OBJECT_CONNECTOR)) {
    for (std::uint32_t i = 0; i < props->count_props; ++i) {
      drmModePropertyRes* p = drmModeGetProperty(fd, props->props[i]);
      if (!p) continue;
      if (std::strcmp(p->name, "non-desktop") == 0) out.info.non_desktop = props->prop_values[i] != 0;
      if (std::strcmp(p->name, "EDID") == 0 && props->prop_values[i] != 0) {
        if (drmModePropertyBlobRes* blob = drmModeGetPropertyBlob(fd, std::uint32_t(props->prop_values[i]))) {
          auto id = parse_edid_identity({static_cast<const std::uint8_t*>(blob->data), blob->length});
          if (id) {
            out.info.edid_vendor = id->vendor;
            out.info.edid_product = id->product;
            out.info.edid_name = id->name;
          }
          drmModeFreePropertyBlob(blob);
        }
      }
      drmModeFreeProperty(p);
    }
    drmModeFreeObjectProperties(props);
  }
  return out;
}

// Opens a card node. Errors name the node and, for permissions, the usual remedy.
Result<int> open_card(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
  if (fd >= 0) return fd;
  const int e = errno;
  if (e == EACCES || e == EPERM)
    return io_error("not permitted to open " + path + " (" + errno_text(e) +
                    "): add the user to group 'video' or run from the local seat (docs/headset.md)");
  if (e == ENOENT) return Error{ErrorKind::device, "no DRM device " + path + " (is the GPU's kernel driver loaded?)"};
  return Error{ErrorKind::device, "cannot open " + path + ": " + errno_text(e)};
}

struct Card {
  std::string driver;
  std::vector<Connector> connectors;
  std::vector<std::uint32_t> crtcs;
};

Result<Card> read_card(int fd, const std::string& path) {
  Card card;
  if (drmVersion* v = drmGetVersion(fd)) {
    card.driver = v->name ? v->name : "";
    drmFreeVersion(v);
  } else {
    return Error{ErrorKind::device, path + " is not a DRM device"};
  }
  drmModeRes* res = drmModeGetResources(fd);
  if (!res) return Error{ErrorKind::device, path + " (" + card.driver + ") has no KMS outputs (a render-only device?)"};
  card.crtcs.assign(res->crtcs, res->crtcs + res->count_crtcs);
  for (int i = 0; i < res->count_connectors; ++i) {
    if (drmModeConnector* c = drmModeGetConnector(fd, res->connectors[i])) {
      card.connectors.push_back(read_connector(fd, c));
      drmModeFreeConnector(c);
    }
  }
  drmModeFreeResources(res);
  return card;
}

std::vector<std::string> card_nodes() {
  std::vector<std::string> nodes;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator("/dev/dri", ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("card", 0) == 0) nodes.push_back(e.path().string());
  }
  std::sort(nodes.begin(), nodes.end());
  return nodes;
}

// A CRTC that can drive the connector: the one already driving it, else an idle one it
// can use, else any it can use (that one's other output goes dark while foveald runs).
std::optional<std::uint32_t> find_crtc(int fd, const Card& card, const Connector& c) {
  if (c.encoder_id) {
    if (drmModeEncoder* enc = drmModeGetEncoder(fd, c.encoder_id)) {
      const std::uint32_t crtc = enc->crtc_id;
      drmModeFreeEncoder(enc);
      if (crtc) return crtc;
    }
  }
  std::optional<std::uint32_t> busy;
  for (std::uint32_t id : c.encoders) {
    drmModeEncoder* enc = drmModeGetEncoder(fd, id);
    if (!enc) continue;
    const std::uint32_t possible = enc->possible_crtcs;
    drmModeFreeEncoder(enc);
    for (std::size_t i = 0; i < card.crtcs.size() && i < 32; ++i) {
      if (!(possible & (1u << i))) continue;
      drmModeCrtc* crtc = drmModeGetCrtc(fd, card.crtcs[i]);
      const bool idle = crtc && crtc->buffer_id == 0;
      if (crtc) drmModeFreeCrtc(crtc);
      if (idle) return card.crtcs[i];
      if (!busy) busy = card.crtcs[i];
    }
  }
  return busy;
}

}  // namespace

struct DrmOutput::Impl {
  std::string path;
  int fd = -1;
  KmsConnector connector;
  KmsMode mode;
  drmModeModeInfo kms_mode{};
  std::uint32_t crtc = 0;
  drmModeCrtc* saved_crtc = nullptr;  // what the CRTC showed before, put back on close
  gbm_device* gbm = nullptr;
  gbm_surface* surface = nullptr;
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  EGLSurface egl_surface = EGL_NO_SURFACE;
  gbm_bo* shown = nullptr;    // on screen
  gbm_bo* pending = nullptr;  // queued by a page flip
  bool mode_set = false;
  PresentStats stats;
  std::int64_t ready_ns = 0;  // the last frame in its buffer

  Status make_gl();

  ~Impl() {
    if (pending) (void)wait_flip(1000);
    if (saved_crtc && mode_set) {
      std::uint32_t conn = connector.id;
      if (saved_crtc->mode_valid && saved_crtc->buffer_id)
        drmModeSetCrtc(fd, crtc, saved_crtc->buffer_id, saved_crtc->x, saved_crtc->y, &conn, 1, &saved_crtc->mode);
      else
        drmModeSetCrtc(fd, crtc, 0, 0, 0, nullptr, 0, nullptr);  // it was off
    }
    if (saved_crtc) drmModeFreeCrtc(saved_crtc);
    if (shown && surface) gbm_surface_release_buffer(surface, shown);
    if (display != EGL_NO_DISPLAY) {
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (egl_surface != EGL_NO_SURFACE) eglDestroySurface(display, egl_surface);
      if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
      eglTerminate(display);
    }
    if (surface) gbm_surface_destroy(surface);
    if (gbm) gbm_device_destroy(gbm);
    if (fd >= 0) ::close(fd);
  }

  // The framebuffer of a GBM buffer, made once and kept with it.
  Result<std::uint32_t> framebuffer(gbm_bo* bo) {
    if (void* fb = gbm_bo_get_user_data(bo)) return static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(fb));
    const std::uint32_t handles[4] = {gbm_bo_get_handle(bo).u32, 0, 0, 0};
    const std::uint32_t pitches[4] = {gbm_bo_get_stride(bo), 0, 0, 0};
    const std::uint32_t offsets[4] = {0, 0, 0, 0};
    std::uint32_t fb = 0;
    if (drmModeAddFB2(fd, gbm_bo_get_width(bo), gbm_bo_get_height(bo), gbm_bo_get_format(bo), handles, pitches,
                      offsets, &fb, 0) != 0)
      return Error{ErrorKind::device, path + ": drmModeAddFB2 failed: " + errno_text(errno)};
    gbm_bo_set_user_data(bo, reinterpret_cast<void*>(std::uintptr_t(fb)), [](gbm_bo* b, void* data) {
      const int dev = gbm_device_get_fd(gbm_bo_get_device(b));
      drmModeRmFB(dev, static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(data)));
    });
    return fb;
  }

  // Waits for the pending flip's event; on it the flipped buffer is shown and the one
  // before goes back to the surface.
  Status wait_flip(int timeout_ms) {
    drmEventContext ev{};
    ev.version = 3;
    ev.page_flip_handler2 = [](int, unsigned sequence, unsigned sec, unsigned usec, unsigned, void* data) {
      auto* self = static_cast<Impl*>(data);
      self->stats.record(std::int64_t(sec) * 1000000000 + std::int64_t(usec) * 1000, sequence);
      if (self->shown) gbm_surface_release_buffer(self->surface, self->shown);
      self->shown = self->pending;
      self->pending = nullptr;
    };
    const std::int64_t deadline = monotonic_now_ns() + std::int64_t(timeout_ms) * 1000000;
    while (pending) {
      const int left = int(std::max<std::int64_t>(0, (deadline - monotonic_now_ns()) / 1000000));
      pollfd p{fd, POLLIN, 0};
      const int r = ::poll(&p, 1, left);
      if (r < 0 && errno == EINTR) continue;
      if (r <= 0) return Error{ErrorKind::device, path + ": no page flip completed within " + std::to_string(timeout_ms) + " ms"};
      if (drmHandleEvent(fd, &ev) != 0) return Error{ErrorKind::device, path + ": reading DRM events failed: " + errno_text(errno)};
    }
    return {};
  }
};

namespace {

std::string busy_message(const std::string& path) {
  return path + " is busy: another process is its DRM master (a desktop compositor or X server). Run from a text "
               "console with no compositor on this GPU, or stop it (docs/headset.md)";
}

// A display whose driver has no vblank still refreshes at its mode's rate: a flip waits
// for the next refresh after the last one shown, so frames are not shown faster than
// the display could and "shown" means the refresh it was flipped at.
void sleep_until_next_refresh(std::int64_t last_ns, double refresh_hz) {
  const auto period = static_cast<std::int64_t>(1e9 / refresh_hz);
  const std::int64_t periods = std::max<std::int64_t>(1, (monotonic_now_ns() - last_ns + period - 1) / period);
  sleep_until_ns(last_ns + periods * period);
}

Status become_master(int fd, const std::string& path) {
  if (drmIsMaster(fd)) return {};
  if (drmSetMaster(fd) == 0) return {};
  return Error{ErrorKind::device, busy_message(path)};
}

EGLConfig gbm_config(EGLDisplay display) {
  const EGLint attribs[] = {EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_RED_SIZE, 8,
                            EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_NONE};
  EGLint n = 0;
  if (!eglChooseConfig(display, attribs, nullptr, 0, &n) || n <= 0) return nullptr;
  std::vector<EGLConfig> configs(static_cast<std::size_t>(n));
  eglChooseConfig(display, attribs, configs.data(), n, &n);
  // The scanout format must be the config's native visual.
  for (EGLint i = 0; i < n; ++i) {
    EGLint visual = 0;
    if (eglGetConfigAttrib(display, configs[std::size_t(i)], EGL_NATIVE_VISUAL_ID, &visual) &&
        static_cast<std::uint32_t>(visual) == GBM_FORMAT_XRGB8888)
      return configs[std::size_t(i)];
  }
  return nullptr;
}

std::vector<KmsConnector> connector_infos(const Card& card) {
  std::vector<KmsConnector> v;
  for (const auto& c : card.connectors) v.push_back(c.info);
  return v;
}

}  // namespace

Result<DrmOutput> DrmOutput::open(const DrmOutputOptions& opt) {
  auto impl = std::make_unique<Impl>();
  std::vector<std::string> nodes = opt.device.empty() ? card_nodes() : std::vector<std::string>{opt.device};
  if (nodes.empty())
    return Error{ErrorKind::device, "no DRM devices in /dev/dri (is the GPU's kernel driver loaded?)"};
  std::string why;
  std::optional<Card> card;
  KmsChoice choice;
  for (const std::string& node : nodes) {
    auto fd = open_card(node);
    if (!fd) {
      if (nodes.size() == 1) return fd.error();
      why += "\n" + fd.error().message;
      continue;
    }
    auto c = read_card(*fd, node);
    Result<KmsChoice> ch = c ? choose_output(connector_infos(*c), opt.wanted) : Result<KmsChoice>(c.error());
    if (!ch) {
      ::close(*fd);
      // read_card's errors name the node already, choose_output's do not.
      const std::string msg = c ? node + ": " + ch.error().message : ch.error().message;
      if (nodes.size() == 1) return Error{ch.error().kind, msg};
      why += "\n" + msg;
      continue;
    }
    impl->fd = *fd;
    impl->path = node;
    card = std::move(*c);
    choice = *ch;
    break;
  }
  if (!card) return Error{ErrorKind::bad_input, "no DRM device has a matching output:" + why};

  const Connector& conn = card->connectors[choice.connector];
  impl->connector = conn.info;
  impl->mode = conn.info.modes[choice.mode];
  impl->kms_mode = conn.modes[choice.mode];
  impl->stats = PresentStats(impl->mode.refresh_hz);
  if (Status s = become_master(impl->fd, impl->path); !s) return s.error();
  auto crtc = find_crtc(impl->fd, *card, conn);
  if (!crtc) return Error{ErrorKind::device, impl->path + ": no CRTC can drive " + conn.info.name};
  impl->crtc = *crtc;
  impl->saved_crtc = drmModeGetCrtc(impl->fd, impl->crtc);
  if (Status s = impl->make_gl(); !s) return s.error();
  return DrmOutput(std::move(impl));
}

Status DrmOutput::Impl::make_gl() {
  Impl& o = *this;
  const int w = o.mode.width, h = o.mode.height;
  o.gbm = gbm_create_device(o.fd);
  if (!o.gbm) return Error{ErrorKind::unsupported, o.path + ": gbm_create_device failed (Mesa's libgbm1 missing?)"};
  o.surface = gbm_surface_create(o.gbm, std::uint32_t(w), std::uint32_t(h), GBM_FORMAT_XRGB8888,
                                 GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
  if (!o.surface) return Error{ErrorKind::unsupported, o.path + ": gbm_surface_create " + std::to_string(w) + "x" + std::to_string(h) + " XRGB8888 failed"};
  auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!gl::has_extension(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS), "EGL_KHR_platform_gbm") ||
      !get_platform_display)
    return Error{ErrorKind::unsupported, "EGL has no GBM platform (EGL_KHR_platform_gbm; Debian: libegl-mesa0)"};
  o.display = get_platform_display(EGL_PLATFORM_GBM_KHR, o.gbm, nullptr);
  if (o.display == EGL_NO_DISPLAY || !eglInitialize(o.display, nullptr, nullptr))
    return Error{ErrorKind::unsupported, gl::egl_error("eglInitialize (GBM platform)")};
  if (!eglBindAPI(EGL_OPENGL_API)) return Error{ErrorKind::unsupported, gl::egl_error("eglBindAPI(EGL_OPENGL_API)")};
  EGLConfig config = gbm_config(o.display);
  if (!config) return Error{ErrorKind::unsupported, "EGL on GBM: no OpenGL window config with an XRGB8888 visual"};
  o.context = eglCreateContext(o.display, config, EGL_NO_CONTEXT, gl::kGl45CoreAttribs);
  if (o.context == EGL_NO_CONTEXT)
    return Error{ErrorKind::unsupported, gl::egl_error("eglCreateContext (OpenGL 4.5 core, GBM)")};
  o.egl_surface = eglCreateWindowSurface(o.display, config, reinterpret_cast<EGLNativeWindowType>(o.surface), nullptr);
  if (o.egl_surface == EGL_NO_SURFACE) return Error{ErrorKind::unsupported, gl::egl_error("eglCreateWindowSurface (GBM)")};
  if (!eglMakeCurrent(o.display, o.egl_surface, o.egl_surface, o.context))
    return Error{ErrorKind::unsupported, gl::egl_error("eglMakeCurrent (GBM)")};
  return {};
}

DrmOutput::DrmOutput(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
DrmOutput::DrmOutput(DrmOutput&&) noexcept = default;
DrmOutput& DrmOutput::operator=(DrmOutput&&) noexcept = default;
DrmOutput::~DrmOutput() = default;

const std::string& DrmOutput::device() const { return impl_->path; }
const KmsConnector& DrmOutput::connector() const { return impl_->connector; }
const KmsMode& DrmOutput::mode() const { return impl_->mode; }
const PresentStats& DrmOutput::stats() const { return impl_->stats; }
std::vector<std::int64_t> DrmOutput::take_shown() { return impl_->stats.take_shown(); }
std::int64_t DrmOutput::last_ready_ns() const { return impl_->ready_ns; }

Status DrmOutput::present(GLuint framebuffer, int width, int height) {
  Impl& o = *impl_;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDisable(GL_FRAMEBUFFER_SRGB);  // copy the sRGB-encoded bytes as they are
  glBlitNamedFramebuffer(framebuffer, 0, 0, 0, width, height, 0, 0, o.mode.width, o.mode.height, GL_COLOR_BUFFER_BIT,
                         GL_LINEAR);
  if (!eglSwapBuffers(o.display, o.egl_surface)) return Error{ErrorKind::device, gl::egl_error("eglSwapBuffers (GBM)")};
  gbm_bo* bo = gbm_surface_lock_front_buffer(o.surface);
  if (!bo) return Error{ErrorKind::device, o.path + ": gbm_surface_lock_front_buffer failed"};
  o.ready_ns = monotonic_now_ns();
  auto fb = o.framebuffer(bo);
  if (!fb) {
    gbm_surface_release_buffer(o.surface, bo);
    return fb.error();
  }
  if (!o.mode_set) {
    std::uint32_t conn = o.connector.id;
    if (drmModeSetCrtc(o.fd, o.crtc, *fb, 0, 0, &conn, 1, &o.kms_mode) != 0) {
      const int e = errno;
      gbm_surface_release_buffer(o.surface, bo);
      if (e == EACCES || e == EPERM || e == EBUSY) return Error{ErrorKind::device, busy_message(o.path)};
      return Error{ErrorKind::device, o.path + ": setting mode " + std::to_string(o.mode.width) + "x" +
                                          std::to_string(o.mode.height) + " on " + o.connector.name +
                                          " failed: " + errno_text(e)};
    }
    o.mode_set = true;
    o.shown = bo;
    o.stats.record(monotonic_now_ns());
    return {};
  }
  if (o.pending) {
    if (Status s = o.wait_flip(1000); !s) {
      gbm_surface_release_buffer(o.surface, bo);
      return s;
    }
  }
  const bool software_vblank = o.stats.fake_vblank() && o.mode.refresh_hz > 0;
  if (software_vblank) sleep_until_next_refresh(*o.stats.last(), o.mode.refresh_hz);
  if (drmModePageFlip(o.fd, o.crtc, *fb, DRM_MODE_PAGE_FLIP_EVENT, &o) != 0) {
    const int e = errno;
    gbm_surface_release_buffer(o.surface, bo);
    if (e == EACCES || e == EPERM) return Error{ErrorKind::device, o.path + ": lost DRM master (a VT switch?)"};
    return Error{ErrorKind::device, o.path + ": page flip failed: " + errno_text(e)};
  }
  o.pending = bo;
  if (software_vblank) return o.wait_flip(1000);  // completes at once: its time is the flip's
  return {};
}

Status DrmOutput::finish() { return impl_->pending ? impl_->wait_flip(1000) : Status{}; }

std::vector<DrmDeviceInfo> DrmOutput::list_devices() {
  std::vector<DrmDeviceInfo> out;
  for (const std::string& node : card_nodes()) {
    DrmDeviceInfo d;
    d.path = node;
    auto fd = open_card(node);
    if (!fd) {
      d.error = fd.error().message;
    } else {
      auto card = read_card(*fd, node);
      if (card) {
        d.driver = card->driver;
        for (auto& c : card->connectors) d.connectors.push_back(std::move(c.info));
      } else {
        d.error = card.error().message;
      }
      ::close(*fd);
    }
    out.push_back(std::move(d));
  }
  return out;
}

Result<std::string> find_headset_connector(const KmsWanted& wanted) {
  std::string seen;
  for (const DrmDeviceInfo& d : DrmOutput::list_devices()) {
    if (auto ch = choose_output(d.connectors, wanted); ch && d.error.empty()) return d.connectors[ch->connector].name;
    seen += "\n  " + d.path + (d.error.empty() ? "" : ": " + d.error);
    for (const auto& c : d.connectors) seen += "\n    " + describe(c);
  }
  return bad_input("no DRM connector offers the display model's " + std::to_string(wanted.width) + "x" +
                   std::to_string(wanted.height) + " mode" + (seen.empty() ? " (no /dev/dri/card* devices)" : ":" + seen));
}

}  // namespace foveal::render

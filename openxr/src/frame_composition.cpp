// xrEndFrame for a session that renders quad views: each 4-view projection layer goes
// down as a 2-view one whose images the layer composed (the inner view blended over the
// upsampled outer one) into stereo swapchains of its own on the runtime, on the app's
// OpenGL context or Vulkan device (composer.hpp). Other layers, the layer flags, the space
// and each view's chain (depth) pass through. docs/openxr.md.
#include "capture.hpp"
#include "quad_session.hpp"

namespace foveal::openxr {

std::uint64_t next_swapchain_serial() {
  static std::atomic<std::uint64_t> serial{0};
  return serial.fetch_add(1, std::memory_order_relaxed) + 1;
}

bool holds_release(const QuadSession* q, const SwapchainRecord* s) {
  return q && s && q->api == QuadSession::Api::vulkan && q->began_quad.load(std::memory_order_acquire) &&
         s->acquired_count > 0 && !s->release_held.load(std::memory_order_acquire);
}

void forward_release(SwapchainRecord& s) {
  if (!s.release_held.exchange(false, std::memory_order_acq_rel)) return;
  s.released.store(-1, std::memory_order_release);
  const XrSwapchain handle = s.handle.load(std::memory_order_acquire);
  XrSwapchainImageReleaseInfo info{XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO, nullptr};
  if (handle != XR_NULL_HANDLE && XR_FAILED(layer().next.ReleaseSwapchainImage(handle, &info)))
    log_line("quad views: the runtime refused an image release the layer had held to xrEndFrame");
}

namespace {

/// Every release held in this session, passed on (after the composition's submits).
void forward_releases(QuadSession& q) {
  if (q.api != QuadSession::Api::vulkan) return;
  for (SwapchainRecord& s : q.swapchains)
    if (s.release_held.load(std::memory_order_acquire)) forward_release(s);
}

/// The images of one of the layer's swapchains, as the session's graphics API names them.
bool enumerate_images(QuadSession& q, XrSwapchain handle, OutputSwapchain& o) {
  Layer& l = layer();
  std::uint32_t n = 0;
  if (q.api == QuadSession::Api::opengl) {
    XrSwapchainImageOpenGLKHR images[8];
    for (auto& i : images) i = {XR_TYPE_SWAPCHAIN_IMAGE_OPENGL_KHR, nullptr, 0};
    if (XR_FAILED(l.next.EnumerateSwapchainImages(handle, 8, &n, reinterpret_cast<XrSwapchainImageBaseHeader*>(images))))
      return false;
    for (std::uint32_t i = 0; i < n; ++i) o.images[i] = images[i].image;
  }
#ifdef FOVEAL_OPENXR_VULKAN
  if (q.api == QuadSession::Api::vulkan) {
    XrSwapchainImageVulkanKHR images[8];
    for (auto& i : images) i = {XR_TYPE_SWAPCHAIN_IMAGE_VULKAN_KHR, nullptr, VK_NULL_HANDLE};
    if (XR_FAILED(l.next.EnumerateSwapchainImages(handle, 8, &n, reinterpret_cast<XrSwapchainImageBaseHeader*>(images))))
      return false;
    for (std::uint32_t i = 0; i < n; ++i) o.images[i] = reinterpret_cast<std::uint64_t>(images[i].image);
  }
#endif
  o.image_count = n;
  return n > 0;
}

/// The layer's swapchain for eye e, made at the first frame in the app's outer format.
bool ensure_output(QuadSession& q, int e, std::int64_t format) {
  OutputSwapchain& o = q.out[e];
  if (o.handle != XR_NULL_HANDLE && o.format == format) return true;
  Layer& l = layer();
  if (o.handle != XR_NULL_HANDLE) l.next.DestroySwapchain(o.handle), o = OutputSwapchain{};
  XrSwapchainCreateInfo info{XR_TYPE_SWAPCHAIN_CREATE_INFO, nullptr, 0,
                             XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT | XR_SWAPCHAIN_USAGE_SAMPLED_BIT,
                             format, 1, q.stereo_w[e], q.stereo_h[e], 1, 1, 1};
  XrSwapchain handle = XR_NULL_HANDLE;
  if (XR_FAILED(l.next.CreateSwapchain(q.session, &info, &handle))) return false;
  if (!enumerate_images(q, handle, o)) {
    l.next.DestroySwapchain(handle);
    o = OutputSwapchain{};
    return false;
  }
  o.handle = handle;
  o.width = q.stereo_w[e];
  o.height = q.stereo_h[e];
  o.serial = next_swapchain_serial();
  o.format = format;
  return true;
}

/// A composer on the session's graphics API, made at its first quad frame.
std::unique_ptr<Composer> make_composer(QuadSession& q, std::string& error) {
#ifdef FOVEAL_OPENXR_VULKAN
  if (q.api == QuadSession::Api::vulkan) return VkComposer::create(q.vk, error);
#endif
  return GlComposer::create(q.get_proc, error);
}

/// The texture and rectangle a view's sub-image names, as the app last released it.
bool source_of(const XrCompositionLayerProjectionView& v, ComposeSource& s, const SwapchainRecord** record) {
  const SwapchainRecord* r = find_swapchain(v.subImage.swapchain);
  if (!r || v.subImage.imageArrayIndex >= r->array_size) return false;
  const int index = r->released.load(std::memory_order_acquire);
  if (index < 0 || static_cast<std::uint32_t>(index) >= r->image_count) return false;
  s.image = r->images[index];
  s.format = r->format;
  s.serial = r->serial;
  s.image_w = static_cast<int>(r->width);
  s.image_h = static_cast<int>(r->height);
  s.x = v.subImage.imageRect.offset.x;
  s.y = v.subImage.imageRect.offset.y;
  s.w = v.subImage.imageRect.extent.width;
  s.h = v.subImage.imageRect.extent.height;
  s.fov = to_tangents(v.fov);
  s.layer = v.subImage.imageArrayIndex;  // array swapchains: the layer the view was drawn into
  s.array = r->array_size > 1;
  if (record) *record = r;
  return s.w > 0 && s.h > 0 && s.image_w > 0 && s.image_h > 0;
}

/// Composes eye e of a quad layer into the layer's swapchain; false: the outer view
/// goes down alone (logged once).
bool compose_eye(QuadSession& q, const XrCompositionLayerProjectionView& outer_view,
                 const XrCompositionLayerProjectionView& inner_view, int e, std::uint64_t& image_out) {
  Layer& l = layer();
  ComposeSource outer, inner;
  const SwapchainRecord* outer_record = nullptr;
  if (!source_of(outer_view, outer, &outer_record) || !source_of(inner_view, inner, nullptr)) return false;
  if (!q.composer && !q.composer_failed) {
    std::string error;
    q.composer = make_composer(q, error);
    if (!q.composer) {
      q.composer_failed = true;
      const std::string line = std::string("quad views: cannot compose on this ") +
                               (q.api == QuadSession::Api::vulkan ? "Vulkan device (" : "OpenGL context (") + error +
                               "): the outer views are shown alone";
      log_line(line.c_str());
    }
  }
  if (!q.composer || !ensure_output(q, e, outer_record->format)) return false;
  OutputSwapchain& o = q.out[e];
  std::uint32_t index = 0;
  XrSwapchainImageAcquireInfo acquire{XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO, nullptr};
  if (XR_FAILED(l.next.AcquireSwapchainImage(o.handle, &acquire, &index)) || index >= o.image_count) return false;
  XrSwapchainImageWaitInfo wait{XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO, nullptr, XR_INFINITE_DURATION};
  bool ok = XR_SUCCEEDED(l.next.WaitSwapchainImage(o.handle, &wait));
  if (ok)
    ok = q.composer->compose(outer, inner,
                             {o.images[index], o.format, o.serial, static_cast<int>(o.width), static_cast<int>(o.height)},
                             outer.fov, q.inset.blend_deg);
  XrSwapchainImageReleaseInfo release{XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO, nullptr};
  l.next.ReleaseSwapchainImage(o.handle, &release);
  image_out = ok ? o.images[index] : 0;
  return ok;
}

}  // namespace

XrResult end_quad_frame(QuadSession& q, const XrFrameEndInfo* info) {
  Layer& l = layer();
  if (!info || info->layerCount == 0 || !info->layers) {
    forward_releases(q);
    return l.next.EndFrame(q.session, info);
  }
  bool any = false;
  for (std::uint32_t i = 0; i < info->layerCount; ++i) {
    const auto* p = info->layers[i];
    any |= p && p->type == XR_TYPE_COMPOSITION_LAYER_PROJECTION &&
           reinterpret_cast<const XrCompositionLayerProjection*>(p)->viewCount == 4;
  }
  if (!any || info->layerCount > kMaxFrameLayers) {
    forward_releases(q);
    if (any) return XR_ERROR_LAYER_LIMIT_EXCEEDED;
    return l.next.EndFrame(q.session, info);  // stereo layers: untouched
  }
  bool composed_one = false;
  std::uint64_t composed[2] = {};
  for (std::uint32_t i = 0; i < info->layerCount; ++i) {
    const auto* p = info->layers[i];
    q.layers[i] = p;
    if (!p || p->type != XR_TYPE_COMPOSITION_LAYER_PROJECTION) continue;
    const auto* proj = reinterpret_cast<const XrCompositionLayerProjection*>(p);
    if (proj->viewCount != 4 || !proj->views) continue;
    XrCompositionLayerProjection& out = q.projection[i];
    out = *proj;
    out.viewCount = 2;
    out.views = q.views[i];
    for (int e = 0; e < 2; ++e) {
      q.views[i][e] = proj->views[e];  // pose, field, chain (depth): the outer view's
      // One set of output swapchains: the first quad layer of a frame is composed.
      bool ok = !composed_one && compose_eye(q, proj->views[e], proj->views[e + 2], e, composed[e]);
      if (ok) {
        q.views[i][e].subImage = {q.out[e].handle, {{0, 0}, {static_cast<std::int32_t>(q.out[e].width),
                                                             static_cast<std::int32_t>(q.out[e].height)}}, 0};
      } else if (!q.said_degraded) {
        q.said_degraded = true;
        log_line("quad views: a 4-view layer could not be composed (an unknown image, an imageArrayIndex past "
                 "the swapchain's arraySize, or a second quad layer in one frame): its outer views are shown alone");
      }
    }
    composed_one = true;
    q.layers[i] = reinterpret_cast<const XrCompositionLayerBaseHeader*>(&out);
  }
  if (composed[0] && composed[1] && !q.capture_dir.empty() && q.frames_composed == q.capture_frame) {
    // Read after the release: fine on GL; a Vulkan runtime has the images by now.
    if (q.api == QuadSession::Api::opengl)
      capture_stereo(*q.composer, composed, q.out, q.capture_dir);
    else
      log_line("capture: FOVEAL_OPENXR_CAPTURE_DIR captures OpenGL sessions only");
  }
  ++q.frames_composed;
  forward_releases(q);
  XrFrameEndInfo down = *info;
  down.layers = q.layers;
  return l.next.EndFrame(q.session, &down);
}

}  // namespace foveal::openxr

// xrEndFrame for a session that renders quad views: each 4-view projection layer goes
// down as a 2-view one whose images the layer composed (the inner view blended over the
// upsampled outer one) into stereo swapchains of its own on the runtime. Other layers,
// the layer flags, the space and each view's chain (depth) pass through. docs/openxr.md.
#include <GL/glcorearb.h>

#include "capture.hpp"
#include "quad_session.hpp"

namespace foveal::openxr {

namespace {

bool is_srgb(std::int64_t format) {
  return format == GL_SRGB8_ALPHA8 || format == GL_SRGB8;
}

/// The layer's swapchain for eye e, made at the first frame in the app's outer format.
bool ensure_output(QuadSession& q, int e, std::int64_t format) {
  OutputSwapchain& o = q.out[e];
  if (o.handle != XR_NULL_HANDLE && q.out_format == format) return true;
  Layer& l = layer();
  if (o.handle != XR_NULL_HANDLE) l.next.DestroySwapchain(o.handle), o = OutputSwapchain{};
  XrSwapchainCreateInfo info{XR_TYPE_SWAPCHAIN_CREATE_INFO, nullptr, 0,
                             XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT | XR_SWAPCHAIN_USAGE_SAMPLED_BIT,
                             format, 1, q.stereo_w[e], q.stereo_h[e], 1, 1, 1};
  if (XR_FAILED(l.next.CreateSwapchain(q.session, &info, &o.handle))) return false;
  XrSwapchainImageOpenGLKHR images[8];
  for (auto& i : images) i = {XR_TYPE_SWAPCHAIN_IMAGE_OPENGL_KHR, nullptr, 0};
  std::uint32_t n = 0;
  if (XR_FAILED(l.next.EnumerateSwapchainImages(o.handle, 8, &n,
                                                reinterpret_cast<XrSwapchainImageBaseHeader*>(images))) ||
      n == 0) {
    l.next.DestroySwapchain(o.handle);
    o = OutputSwapchain{};
    return false;
  }
  o.width = q.stereo_w[e];
  o.height = q.stereo_h[e];
  o.image_count = n;
  for (std::uint32_t i = 0; i < n; ++i) o.images[i] = images[i].image;
  q.out_format = format;
  return true;
}

/// The texture and rectangle a view's sub-image names, as the app last released it.
bool source_of(const XrCompositionLayerProjectionView& v, ComposeSource& s, const SwapchainRecord** record) {
  const SwapchainRecord* r = find_swapchain(v.subImage.swapchain);
  if (!r || r->array_size != 1 || v.subImage.imageArrayIndex != 0) return false;
  const int index = r->released.load(std::memory_order_acquire);
  if (index < 0 || static_cast<std::uint32_t>(index) >= r->image_count) return false;
  s.texture = r->images[index];
  s.image_w = static_cast<int>(r->width);
  s.image_h = static_cast<int>(r->height);
  s.x = v.subImage.imageRect.offset.x;
  s.y = v.subImage.imageRect.offset.y;
  s.w = v.subImage.imageRect.extent.width;
  s.h = v.subImage.imageRect.extent.height;
  s.fov = to_tangents(v.fov);
  if (record) *record = r;
  return s.w > 0 && s.h > 0 && s.image_w > 0 && s.image_h > 0;
}

/// Composes eye e of a quad layer into the layer's swapchain; false: the outer view
/// goes down alone (logged once).
bool compose_eye(QuadSession& q, const XrCompositionLayerProjectionView& outer_view,
                 const XrCompositionLayerProjectionView& inner_view, int e, std::uint32_t& image_out) {
  Layer& l = layer();
  ComposeSource outer, inner;
  const SwapchainRecord* outer_record = nullptr;
  if (!source_of(outer_view, outer, &outer_record) || !source_of(inner_view, inner, nullptr)) return false;
  if (!q.composer && !q.composer_failed) {
    std::string error;
    q.composer = GlComposer::create(q.get_proc, error);
    if (!q.composer) {
      q.composer_failed = true;
      const std::string line = "quad views: cannot compose on this OpenGL context (" + error + "): the outer views are shown alone";
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
    ok = q.composer->compose(outer, inner, o.images[index], static_cast<int>(o.width), static_cast<int>(o.height),
                             outer.fov, q.inset.blend_deg, is_srgb(outer_record->format));
  XrSwapchainImageReleaseInfo release{XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO, nullptr};
  l.next.ReleaseSwapchainImage(o.handle, &release);
  image_out = ok ? o.images[index] : 0;
  return ok;
}

}  // namespace

XrResult end_quad_frame(QuadSession& q, const XrFrameEndInfo* info) {
  Layer& l = layer();
  if (!info || info->layerCount == 0 || !info->layers) return l.next.EndFrame(q.session, info);
  bool any = false;
  for (std::uint32_t i = 0; i < info->layerCount; ++i) {
    const auto* p = info->layers[i];
    any |= p && p->type == XR_TYPE_COMPOSITION_LAYER_PROJECTION &&
           reinterpret_cast<const XrCompositionLayerProjection*>(p)->viewCount == 4;
  }
  if (!any) return l.next.EndFrame(q.session, info);  // stereo layers: untouched
  if (info->layerCount > kMaxFrameLayers) return XR_ERROR_LAYER_LIMIT_EXCEEDED;
  bool composed_one = false;
  std::uint32_t composed[2] = {};
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
        log_line("quad views: a 4-view layer could not be composed (an array swapchain, an unknown image, or a "
                 "second quad layer in one frame): its outer views are shown alone");
      }
    }
    composed_one = true;
    q.layers[i] = reinterpret_cast<const XrCompositionLayerBaseHeader*>(&out);
  }
  if (composed[0] && composed[1] && !q.capture_dir.empty() && q.frames_composed == q.capture_frame)
    capture_stereo(*q.composer, composed, q.out, q.capture_dir);
  ++q.frames_composed;
  XrFrameEndInfo down = *info;
  down.layers = q.layers;
  return l.next.EndFrame(q.session, &down);
}

}  // namespace foveal::openxr

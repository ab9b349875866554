#pragma once
// The quad views of one session: the runtime's stereo sizes, the inset's motion per eye,
// the app's swapchains (their images, and which one each last released), and what the
// layer submits in their place (quad_views.cpp, frame_composition.cpp).
#include <EGL/egl.h>
#define XR_USE_PLATFORM_EGL          // XrGraphicsBindingEGLMNDX
#define XR_USE_GRAPHICS_API_OPENGL   // XrSwapchainImageOpenGLKHR
#ifdef FOVEAL_OPENXR_VULKAN
#include <vulkan/vulkan.h>
#define XR_USE_GRAPHICS_API_VULKAN   // XrGraphicsBindingVulkanKHR, XrSwapchainImageVulkanKHR
#endif
#include "layer.hpp"

#include <array>
#include <atomic>
#include <memory>
#include <string>

#include "composer.hpp"
#include "gl_composer.hpp"
#include "inset.hpp"
#ifdef FOVEAL_OPENXR_VULKAN
#include "vk_composer.hpp"
#endif

namespace foveal::openxr {

/// An app's swapchain: its images and the order of acquire and release (the
/// specification's rule: released in the order acquired).
struct SwapchainRecord {
  std::atomic<XrSwapchain> handle{XR_NULL_HANDLE};
  std::int64_t format = 0;
  std::uint32_t width = 0, height = 0, array_size = 1;
  std::uint32_t image_count = 0;
  std::uint64_t images[8] = {};  ///< GL texture names or VkImages
  std::uint64_t serial = 0;      ///< new for every swapchain (the Vulkan composer's view cache)
  int acquired[8] = {};
  int acquired_head = 0, acquired_count = 0;
  std::atomic<int> released{-1};  ///< the image its last xrReleaseSwapchainImage gave back
  /// Vulkan: the app released an image that the runtime has not been told of yet. A Vulkan
  /// runtime takes the image off the app's queue at release (Monado: to another layout and
  /// queue family), so the layer samples it first and releases it at xrEndFrame.
  std::atomic<bool> release_held{false};
};

/// The layer's own stereo swapchain for one eye.
struct OutputSwapchain {
  XrSwapchain handle = XR_NULL_HANDLE;
  std::uint32_t width = 0, height = 0, image_count = 0;
  std::int64_t format = 0;
  std::uint64_t images[8] = {};
  std::uint64_t serial = 0;
};

/// A serial no swapchain had before (SwapchainRecord::serial).
std::uint64_t next_swapchain_serial();

constexpr int kMaxFrameLayers = 16;

struct QuadSession {
  enum class Api { unknown, opengl, vulkan };
  XrSession session = XR_NULL_HANDLE;
  Api api = Api::unknown;
  GlGetProcAddress get_proc = nullptr;
#ifdef FOVEAL_OPENXR_VULKAN
  VkBinding vk;  ///< from XrGraphicsBindingVulkanKHR (XR_KHR_vulkan_enable2's is the same struct)
#endif
  std::atomic<bool> began_quad{false};
  std::uint32_t stereo_w[2] = {}, stereo_h[2] = {};
  InsetSettings inset;
  InsetMotion motion[2];
  std::array<SwapchainRecord, 32> swapchains;
  // Composition (the thread that calls xrEndFrame only).
  OutputSwapchain out[2];
  std::unique_ptr<Composer> composer;
  bool composer_failed = false, said_degraded = false;
  long frames_composed = 0;
  std::string capture_dir;  ///< FOVEAL_OPENXR_CAPTURE_DIR: where the capture goes
  long capture_frame = -1;  ///< FOVEAL_OPENXR_CAPTURE_FRAME: which composed frame
  XrCompositionLayerProjection projection[kMaxFrameLayers];
  XrCompositionLayerProjectionView views[kMaxFrameLayers][2];
  const XrCompositionLayerBaseHeader* layers[kMaxFrameLayers];
};

/// The swapchain record of `s` in any session, or null. Lock-free.
SwapchainRecord* find_swapchain(XrSwapchain s, QuadSession** session = nullptr);

/// Vulkan quad sessions: whether xrReleaseSwapchainImage of `s` waits for xrEndFrame.
bool holds_release(const QuadSession* q, const SwapchainRecord* s);
/// Passes a held release of `s` on to the runtime; the image is then no longer the
/// layer's to sample.
void forward_release(SwapchainRecord& s);

/// xrEndFrame for a quad session: 4-view projection layers composed into stereo ones
/// (frame_composition.cpp).
XrResult end_quad_frame(QuadSession& q, const XrFrameEndInfo* info);

/// The inset for one eye's locate: the view (pose, outer field), the head in the same
/// space, and the gaze; fills the inner field.
bool gaze_tangent_in_view(const XrPosef& view_pose, const XrPosef& head_pose, const XrVector3f& gaze_in_head, float& tx,
                          float& ty);

}  // namespace foveal::openxr

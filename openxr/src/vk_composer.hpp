#pragma once
// Quad views composed on the app's Vulkan device (composer.hpp), with the queue the app
// named in its graphics binding (XR_KHR_vulkan_enable2): the OpenXR call that composes
// holds the queue, as the binding's rules say. Sources and targets are swapchain images in
// VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL (where OpenXR leaves them) and are left so.
// The pipeline, descriptor sets and command buffers are made at the first frame; a frame
// records into one of a ring of command buffers, each with a fence, and allocates nothing
// (a view of an image, or of one layer of an array image, is made the first time it is
// seen, and kept).
#include <vulkan/vulkan.h>

#include <array>
#include <memory>
#include <string>

#include "composer.hpp"

namespace foveal::openxr {

/// The app's device, as XrGraphicsBindingVulkanKHR names it.
struct VkBinding {
  PFN_vkGetInstanceProcAddr get_instance_proc = nullptr;
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  std::uint32_t queue_family = 0, queue_index = 0;
};

class VkComposer final : public Composer {
 public:
  /// Loads the device's entry points and makes the sampler, layouts, command buffers and
  /// fences; null with `error` set when it cannot.
  static std::unique_ptr<VkComposer> create(const VkBinding& binding, std::string& error);
  ~VkComposer() override;
  VkComposer(const VkComposer&) = delete;
  VkComposer& operator=(const VkComposer&) = delete;

  /// image: a VkImage (cast); format: its VkFormat. An sRGB target is encoded on write.
  /// False (nothing drawn) when the previous use of this frame's command buffer has not
  /// finished within a second, or a Vulkan call fails.
  bool compose(const ComposeSource& outer, const ComposeSource& inner, const ComposeTarget& target, const TanRect& out,
               float blend_deg) override;
  /// RGBA8/BGRA8 targets (UNORM or sRGB) only.
  bool read(const ComposeTarget& target, std::vector<std::uint8_t>& rgba) override;
  /// Waits until every submitted composition has finished (the benchmark's clock).
  bool finish();

 private:
  VkComposer() = default;
  struct Vk;
  struct CachedView {
    std::uint64_t image = 0, serial = 0, used = 0;
    std::int64_t format = 0;
    std::uint32_t layer = 0;  ///< the array layer the view shows (an array swapchain's imageArrayIndex)
    VkImageView view = VK_NULL_HANDLE;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    int w = 0, h = 0;
  };
  struct Slot {
    VkCommandBuffer commands = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
  };
  static constexpr int kSlots = 4;  // two eyes a frame, two frames in flight

  CachedView* view_of(std::uint64_t image, std::uint64_t serial, std::int64_t format, std::uint32_t layer = 0);
  bool framebuffer_of(CachedView& v, int w, int h);
  bool ensure_pipeline(std::int64_t format);
  bool wait_slot(const Slot& s, std::uint64_t timeout_ns);
  void destroy_pipeline();

  std::unique_ptr<Vk> vk_;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkSampler sampler_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout pipeline_layout_ = VK_NULL_HANDLE;
  VkDescriptorPool descriptor_pool_ = VK_NULL_HANDLE;
  VkCommandPool command_pool_ = VK_NULL_HANDLE;
  VkShaderModule vertex_ = VK_NULL_HANDLE, fragment_ = VK_NULL_HANDLE;
  std::int64_t pipeline_format_ = 0;
  VkRenderPass render_pass_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  std::array<Slot, kSlots> slots_{};
  std::array<CachedView, 48> views_{};
  std::uint64_t uses_ = 0;
  int next_slot_ = 0;
};

}  // namespace foveal::openxr

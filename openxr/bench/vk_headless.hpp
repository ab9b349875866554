#pragma once
// A Vulkan device with no window, for the Vulkan composer's test and benchmark: the
// first CPU device (lavapipe) where there is one, else the first with a graphics queue,
// and images made and filled the way an OpenXR runtime hands them to an app (in
// VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL). Links libvulkan, unlike the layer.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "vk_composer.hpp"

namespace foveal::openxr {

class VkHeadless {
 public:
  /// Null with `error` naming what is missing (no loader, no device, no graphics queue).
  static std::unique_ptr<VkHeadless> create(std::string& error);
  ~VkHeadless();
  VkHeadless(const VkHeadless&) = delete;
  VkHeadless& operator=(const VkHeadless&) = delete;

  VkBinding binding() const;
  const std::string& device_name() const { return name_; }
  /// A w×h image of `format` (4 bytes a pixel) with `layers` array layers, `rgba` each
  /// layer in turn, top row first (or left undefined when null), usable as an attachment,
  /// sampled and copied; owned by this object.
  VkImage image(int w, int h, VkFormat format, const std::uint8_t* rgba, int layers = 1);

 private:
  VkHeadless() = default;
  bool submit_and_wait(VkCommandBuffer cb);
  VkInstance instance_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  std::uint32_t family_ = 0;
  std::string name_;
  struct Owned {
    VkImage image;
    VkDeviceMemory memory;
  };
  std::vector<Owned> images_;
};

}  // namespace foveal::openxr

#include "vk_headless.hpp"

#include <cstring>

namespace foveal::openxr {

namespace {

std::uint32_t memory_type(VkPhysicalDevice physical, std::uint32_t bits, VkMemoryPropertyFlags want) {
  VkPhysicalDeviceMemoryProperties props;
  vkGetPhysicalDeviceMemoryProperties(physical, &props);
  for (std::uint32_t i = 0; i < props.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & want) == want) return i;
  return UINT32_MAX;
}

}  // namespace

std::unique_ptr<VkHeadless> VkHeadless::create(std::string& error) {
  std::unique_ptr<VkHeadless> h(new VkHeadless);
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO, nullptr, "foveal", 1, "foveal", 1, VK_API_VERSION_1_1};
  VkInstanceCreateInfo ii{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, nullptr, 0, &app, 0, nullptr, 0, nullptr};
  if (VkResult r = vkCreateInstance(&ii, nullptr, &h->instance_); r != VK_SUCCESS) {
    error = "vkCreateInstance failed (VkResult " + std::to_string(static_cast<int>(r)) +
            "): no Vulkan driver (Debian: mesa-vulkan-drivers gives lavapipe)";
    return nullptr;
  }
  std::uint32_t n = 0;
  vkEnumeratePhysicalDevices(h->instance_, &n, nullptr);
  std::vector<VkPhysicalDevice> devices(n);
  vkEnumeratePhysicalDevices(h->instance_, &n, devices.data());
  // A CPU device first: the same rasteriser family as Mesa's llvmpipe, which the GL side uses.
  for (int pass = 0; pass < 2 && !h->physical_; ++pass)
    for (VkPhysicalDevice d : devices) {
      VkPhysicalDeviceProperties p;
      vkGetPhysicalDeviceProperties(d, &p);
      if (pass == 0 && p.deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU) continue;
      std::uint32_t qn = 0;
      vkGetPhysicalDeviceQueueFamilyProperties(d, &qn, nullptr);
      std::vector<VkQueueFamilyProperties> families(qn);
      vkGetPhysicalDeviceQueueFamilyProperties(d, &qn, families.data());
      for (std::uint32_t f = 0; f < qn; ++f)
        if (families[f].queueFlags & VK_QUEUE_GRAPHICS_BIT) {
          h->physical_ = d;
          h->family_ = f;
          h->name_ = p.deviceName;
          break;
        }
      if (h->physical_) break;
    }
  if (!h->physical_) {
    error = "no Vulkan physical device with a graphics queue (" + std::to_string(n) +
            " devices; Debian: mesa-vulkan-drivers gives lavapipe)";
    return nullptr;
  }
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo qi{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, nullptr, 0, h->family_, 1, &priority};
  VkDeviceCreateInfo di{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, nullptr, 0, 1, &qi, 0, nullptr, 0, nullptr, nullptr};
  if (VkResult r = vkCreateDevice(h->physical_, &di, nullptr, &h->device_); r != VK_SUCCESS) {
    error = "vkCreateDevice on " + h->name_ + " failed (VkResult " + std::to_string(static_cast<int>(r)) + ")";
    return nullptr;
  }
  vkGetDeviceQueue(h->device_, h->family_, 0, &h->queue_);
  VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr, 0, h->family_};
  if (vkCreateCommandPool(h->device_, &pi, nullptr, &h->pool_) != VK_SUCCESS) {
    error = "vkCreateCommandPool failed";
    return nullptr;
  }
  return h;
}

VkHeadless::~VkHeadless() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    for (const Owned& o : images_) {
      vkDestroyImage(device_, o.image, nullptr);
      vkFreeMemory(device_, o.memory, nullptr);
    }
    if (pool_) vkDestroyCommandPool(device_, pool_, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
}

VkBinding VkHeadless::binding() const { return {vkGetInstanceProcAddr, instance_, physical_, device_, family_, 0}; }

bool VkHeadless::submit_and_wait(VkCommandBuffer cb) {
  VkSubmitInfo si{};
  si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cb;
  const bool ok = vkQueueSubmit(queue_, 1, &si, VK_NULL_HANDLE) == VK_SUCCESS && vkQueueWaitIdle(queue_) == VK_SUCCESS;
  vkFreeCommandBuffers(device_, pool_, 1, &cb);
  return ok;
}

VkImage VkHeadless::image(int w, int h, VkFormat format, const std::uint8_t* rgba, int layers) {
  VkImageCreateInfo ii{};
  ii.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
  ii.imageType = VK_IMAGE_TYPE_2D;
  ii.format = format;
  ii.extent = {static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h), 1};
  ii.mipLevels = 1;
  ii.arrayLayers = static_cast<std::uint32_t>(layers);
  ii.samples = VK_SAMPLE_COUNT_1_BIT;
  ii.tiling = VK_IMAGE_TILING_OPTIMAL;
  ii.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
             VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  ii.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  Owned o{};
  if (vkCreateImage(device_, &ii, nullptr, &o.image) != VK_SUCCESS) return VK_NULL_HANDLE;
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device_, o.image, &req);
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size,
                          memory_type(physical_, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)};
  if (ai.memoryTypeIndex == UINT32_MAX || vkAllocateMemory(device_, &ai, nullptr, &o.memory) != VK_SUCCESS) {
    vkDestroyImage(device_, o.image, nullptr);
    return VK_NULL_HANDLE;
  }
  vkBindImageMemory(device_, o.image, o.memory, 0);
  images_.push_back(o);

  // Staging buffer (when filled), then the copy and the layout OpenXR hands images over in.
  const VkDeviceSize size = static_cast<VkDeviceSize>(w) * static_cast<VkDeviceSize>(h) * 4 * static_cast<VkDeviceSize>(layers);
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory staging = VK_NULL_HANDLE;
  if (rgba) {
    VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, nullptr, 0, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                          VK_SHARING_MODE_EXCLUSIVE, 0, nullptr};
    vkCreateBuffer(device_, &bi, nullptr, &buffer);
    VkMemoryRequirements breq;
    vkGetBufferMemoryRequirements(device_, buffer, &breq);
    VkMemoryAllocateInfo bai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, breq.size,
                             memory_type(physical_, breq.memoryTypeBits,
                                         VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT)};
    vkAllocateMemory(device_, &bai, nullptr, &staging);
    vkBindBufferMemory(device_, buffer, staging, 0);
    void* mapped = nullptr;
    vkMapMemory(device_, staging, 0, size, 0, &mapped);
    std::memcpy(mapped, rgba, static_cast<std::size_t>(size));
    vkUnmapMemory(device_, staging);
  }
  VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, pool_,
                                  VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
  VkCommandBuffer cb = VK_NULL_HANDLE;
  vkAllocateCommandBuffers(device_, &cai, &cb);
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr,
                                 VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT, nullptr};
  vkBeginCommandBuffer(cb, &begin);
  VkImageMemoryBarrier b{};
  b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = o.image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, ii.arrayLayers};
  b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  b.newLayout = rgba ? VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  b.dstAccessMask = rgba ? VK_ACCESS_TRANSFER_WRITE_BIT : VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0,
                       nullptr, 1, &b);
  if (rgba) {
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, ii.arrayLayers};  // the layers follow each other
    region.imageExtent = ii.extent;
    vkCmdCopyBufferToImage(cb, buffer, o.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    b.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    b.newLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, 0,
                         nullptr, 0, nullptr, 1, &b);
  }
  vkEndCommandBuffer(cb);
  const bool ok = submit_and_wait(cb);
  if (buffer) vkDestroyBuffer(device_, buffer, nullptr);
  if (staging) vkFreeMemory(device_, staging, nullptr);
  return ok ? o.image : VK_NULL_HANDLE;
}

}  // namespace foveal::openxr

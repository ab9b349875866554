#include "vk_composer.hpp"

#include <cstdint>
#include <cstring>
#include <utility>

// compose.glsl compiled to SPIR-V by the build (openxr/CMakeLists.txt).
#include "compose_frag_spv.h"
#include "compose_vert_spv.h"

namespace foveal::openxr {

// Every device function the composer calls, loaded through vkGetDeviceProcAddr.
#define FOVEAL_VK_DEVICE_FUNCTIONS(X)                                                                           \
  X(GetDeviceQueue) X(CreateImageView) X(DestroyImageView) X(CreateFramebuffer) X(DestroyFramebuffer)            \
  X(CreateRenderPass) X(DestroyRenderPass) X(CreatePipelineLayout) X(DestroyPipelineLayout)                      \
  X(CreateGraphicsPipelines) X(DestroyPipeline) X(CreateShaderModule) X(DestroyShaderModule)                     \
  X(CreateDescriptorSetLayout) X(DestroyDescriptorSetLayout) X(CreateDescriptorPool) X(DestroyDescriptorPool)    \
  X(AllocateDescriptorSets) X(UpdateDescriptorSets) X(CreateSampler) X(DestroySampler) X(CreateCommandPool)      \
  X(DestroyCommandPool) X(AllocateCommandBuffers) X(ResetCommandBuffer) X(BeginCommandBuffer)                    \
  X(EndCommandBuffer) X(CmdPipelineBarrier) X(CmdBeginRenderPass) X(CmdEndRenderPass) X(CmdBindPipeline)         \
  X(CmdBindDescriptorSets) X(CmdPushConstants) X(CmdSetViewport) X(CmdSetScissor) X(CmdDraw)                    \
  X(CmdCopyImageToBuffer) X(CreateFence) X(DestroyFence) X(WaitForFences) X(ResetFences) X(QueueSubmit)          \
  X(CreateBuffer) X(DestroyBuffer) X(GetBufferMemoryRequirements) X(AllocateMemory) X(FreeMemory)                \
  X(BindBufferMemory) X(MapMemory) X(UnmapMemory)

struct VkComposer::Vk {
  PFN_vkGetPhysicalDeviceMemoryProperties GetPhysicalDeviceMemoryProperties = nullptr;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
#define FOVEAL_VK_MEMBER(name) PFN_vk##name name = nullptr;
  FOVEAL_VK_DEVICE_FUNCTIONS(FOVEAL_VK_MEMBER)
#undef FOVEAL_VK_MEMBER
};

namespace {

/// The shader's push constants (compose.glsl's Params, std430).
struct Params {
  float out_tan[4], outer_tan[4], inner_tan[4], outer_uv[4], inner_uv[4];
  float out_size[2];
  float band;
};
static_assert(sizeof(Params) == 92);

/// Vulkan's images run top-down: the up/down tangents of the output swap, and a source's
/// rectangle is stated from its upper left (compose.glsl's note).
void set_uv(float uv[4], const ComposeSource& s) {
  const float iw = 1.0f / static_cast<float>(s.image_w), ih = 1.0f / static_cast<float>(s.image_h);
  uv[0] = static_cast<float>(s.x) * iw;
  uv[1] = static_cast<float>(s.y + s.h) * ih;
  uv[2] = static_cast<float>(s.w) * iw;
  uv[3] = -static_cast<float>(s.h) * ih;
}

void set_rect(float v[4], const TanRect& t) { v[0] = t.left, v[1] = t.right, v[2] = t.down, v[3] = t.up; }

VkImageMemoryBarrier layout_barrier(VkImage image, VkImageLayout from, VkImageLayout to, VkAccessFlags src,
                                    VkAccessFlags dst, std::uint32_t layer = 0) {
  VkImageMemoryBarrier b{};
  b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
  b.srcAccessMask = src;
  b.dstAccessMask = dst;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, layer, 1};
  return b;
}

constexpr std::uint64_t kSecond = 1'000'000'000;

}  // namespace

std::unique_ptr<VkComposer> VkComposer::create(const VkBinding& b, std::string& error) {
  if (!b.get_instance_proc || !b.instance || !b.physical || !b.device) {
    error = "the Vulkan graphics binding lacks its instance, physical device or device";
    return nullptr;
  }
  std::unique_ptr<VkComposer> c(new VkComposer);
  c->vk_ = std::make_unique<Vk>();
  Vk& vk = *c->vk_;
  vk.physical = b.physical;
  auto get_device_proc =
      reinterpret_cast<PFN_vkGetDeviceProcAddr>(b.get_instance_proc(b.instance, "vkGetDeviceProcAddr"));
  vk.GetPhysicalDeviceMemoryProperties = reinterpret_cast<PFN_vkGetPhysicalDeviceMemoryProperties>(
      b.get_instance_proc(b.instance, "vkGetPhysicalDeviceMemoryProperties"));
  if (!get_device_proc || !vk.GetPhysicalDeviceMemoryProperties) {
    error = "the app's Vulkan instance gives no vkGetDeviceProcAddr or vkGetPhysicalDeviceMemoryProperties";
    return nullptr;
  }
#define FOVEAL_VK_LOAD(name)                                                               \
  vk.name = reinterpret_cast<PFN_vk##name>(get_device_proc(b.device, "vk" #name));        \
  if (!vk.name) {                                                                          \
    error = "the app's Vulkan device lacks vk" #name;                                      \
    return nullptr;                                                                        \
  }
  FOVEAL_VK_DEVICE_FUNCTIONS(FOVEAL_VK_LOAD)
#undef FOVEAL_VK_LOAD
  c->device_ = b.device;
  vk.GetDeviceQueue(b.device, b.queue_family, b.queue_index, &c->queue_);
  if (!c->queue_) {
    error = "the Vulkan binding's queue family/index names no queue";
    return nullptr;
  }
  auto fail = [&](const char* what, VkResult r) {
    error = std::string("Vulkan composer: ") + what + " failed (VkResult " + std::to_string(static_cast<int>(r)) + ")";
    return nullptr;  // the destructor frees what was made
  };
  VkResult r;
  VkSamplerCreateInfo si{};
  si.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
  si.magFilter = si.minFilter = VK_FILTER_LINEAR;  // bilinear, as the GL composer's sampler
  si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  si.maxLod = 0.0f;
  if ((r = vk.CreateSampler(b.device, &si, nullptr, &c->sampler_)) != VK_SUCCESS) return fail("vkCreateSampler", r);

  VkDescriptorSetLayoutBinding bindings[2]{};
  for (std::uint32_t i = 0; i < 2; ++i)
    bindings[i] = {i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, nullptr, 0, 2, bindings};
  if ((r = vk.CreateDescriptorSetLayout(b.device, &li, nullptr, &c->set_layout_)) != VK_SUCCESS)
    return fail("vkCreateDescriptorSetLayout", r);
  const VkPushConstantRange push{VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(Params)};
  VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, nullptr, 0, 1, &c->set_layout_, 1, &push};
  if ((r = vk.CreatePipelineLayout(b.device, &pli, nullptr, &c->pipeline_layout_)) != VK_SUCCESS)
    return fail("vkCreatePipelineLayout", r);
  const VkDescriptorPoolSize pool_size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2 * kSlots};
  VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, nullptr, 0, kSlots, 1, &pool_size};
  if ((r = vk.CreateDescriptorPool(b.device, &dpi, nullptr, &c->descriptor_pool_)) != VK_SUCCESS)
    return fail("vkCreateDescriptorPool", r);
  VkCommandPoolCreateInfo cpi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr,
                              VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT, b.queue_family};
  if ((r = vk.CreateCommandPool(b.device, &cpi, nullptr, &c->command_pool_)) != VK_SUCCESS)
    return fail("vkCreateCommandPool", r);
  for (Slot& s : c->slots_) {
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, c->command_pool_,
                                   VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
    if ((r = vk.AllocateCommandBuffers(b.device, &ai, &s.commands)) != VK_SUCCESS)
      return fail("vkAllocateCommandBuffers", r);
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, nullptr, VK_FENCE_CREATE_SIGNALED_BIT};
    if ((r = vk.CreateFence(b.device, &fi, nullptr, &s.fence)) != VK_SUCCESS) return fail("vkCreateFence", r);
    VkDescriptorSetAllocateInfo dai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO, nullptr, c->descriptor_pool_, 1,
                                    &c->set_layout_};
    if ((r = vk.AllocateDescriptorSets(b.device, &dai, &s.set)) != VK_SUCCESS)
      return fail("vkAllocateDescriptorSets", r);
  }
  VkShaderModuleCreateInfo mi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, nullptr, 0, sizeof foveal_compose_vert_spv,
                              foveal_compose_vert_spv};
  if ((r = vk.CreateShaderModule(b.device, &mi, nullptr, &c->vertex_)) != VK_SUCCESS)
    return fail("vkCreateShaderModule (vertex)", r);
  mi.codeSize = sizeof foveal_compose_frag_spv;
  mi.pCode = foveal_compose_frag_spv;
  if ((r = vk.CreateShaderModule(b.device, &mi, nullptr, &c->fragment_)) != VK_SUCCESS)
    return fail("vkCreateShaderModule (fragment)", r);
  return c;
}

VkComposer::~VkComposer() {
  if (!vk_ || !device_ || !vk_->DestroyFence) return;
  const Vk& vk = *vk_;
  for (const Slot& s : slots_)
    if (s.fence) wait_slot(s, kSecond);  // nothing of ours may still run on the app's queue
  destroy_pipeline();
  for (CachedView& v : views_)
    if (v.view) vk.DestroyImageView(device_, v.view, nullptr);
  for (const Slot& s : slots_)
    if (s.fence) vk.DestroyFence(device_, s.fence, nullptr);
  if (command_pool_) vk.DestroyCommandPool(device_, command_pool_, nullptr);  // frees the command buffers
  if (descriptor_pool_) vk.DestroyDescriptorPool(device_, descriptor_pool_, nullptr);  // and the sets
  if (vertex_) vk.DestroyShaderModule(device_, vertex_, nullptr);
  if (fragment_) vk.DestroyShaderModule(device_, fragment_, nullptr);
  if (pipeline_layout_) vk.DestroyPipelineLayout(device_, pipeline_layout_, nullptr);
  if (set_layout_) vk.DestroyDescriptorSetLayout(device_, set_layout_, nullptr);
  if (sampler_) vk.DestroySampler(device_, sampler_, nullptr);
}

bool VkComposer::wait_slot(const Slot& s, std::uint64_t timeout_ns) {
  return vk_->WaitForFences(device_, 1, &s.fence, VK_TRUE, timeout_ns) == VK_SUCCESS;
}

bool VkComposer::finish() {
  bool ok = true;
  for (const Slot& s : slots_) ok &= wait_slot(s, 10 * kSecond);
  return ok;
}

void VkComposer::destroy_pipeline() {
  const Vk& vk = *vk_;
  for (CachedView& v : views_)
    if (v.framebuffer) vk.DestroyFramebuffer(device_, v.framebuffer, nullptr), v.framebuffer = VK_NULL_HANDLE;
  if (pipeline_) vk.DestroyPipeline(device_, pipeline_, nullptr);
  if (render_pass_) vk.DestroyRenderPass(device_, render_pass_, nullptr);
  pipeline_ = VK_NULL_HANDLE;
  render_pass_ = VK_NULL_HANDLE;
  pipeline_format_ = 0;
}

VkComposer::CachedView* VkComposer::view_of(std::uint64_t image, std::uint64_t serial, std::int64_t format,
                                             std::uint32_t layer) {
  CachedView* oldest = &views_[0];
  for (CachedView& v : views_) {
    if (v.view && v.image == image && v.serial == serial && v.format == format && v.layer == layer) {
      v.used = ++uses_;
      return &v;
    }
    if (v.used < oldest->used) oldest = &v;
  }
  // A new image (the app's swapchains are made once, so this is their first frames):
  // the least recently used entry goes, after everything that may use it has finished.
  const Vk& vk = *vk_;
  if (oldest->view) {
    if (!finish()) return nullptr;
    if (oldest->framebuffer) vk.DestroyFramebuffer(device_, oldest->framebuffer, nullptr);
    vk.DestroyImageView(device_, oldest->view, nullptr);
    *oldest = CachedView{};
  }
  VkImageViewCreateInfo vi{};
  vi.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
  vi.image = reinterpret_cast<VkImage>(image);
  vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vi.format = static_cast<VkFormat>(format);
  vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, layer, 1};  // a 2D view of one layer
  if (vk.CreateImageView(device_, &vi, nullptr, &oldest->view) != VK_SUCCESS) return nullptr;
  oldest->image = image;
  oldest->layer = layer;
  oldest->serial = serial;
  oldest->format = format;
  oldest->used = ++uses_;
  return oldest;
}

bool VkComposer::framebuffer_of(CachedView& v, int w, int h) {
  if (v.framebuffer && v.w == w && v.h == h) return true;
  if (v.framebuffer) {
    if (!finish()) return false;
    vk_->DestroyFramebuffer(device_, v.framebuffer, nullptr);
    v.framebuffer = VK_NULL_HANDLE;
  }
  VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO, nullptr, 0, render_pass_, 1, &v.view,
                             static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h), 1};
  if (vk_->CreateFramebuffer(device_, &fi, nullptr, &v.framebuffer) != VK_SUCCESS) return false;
  v.w = w;
  v.h = h;
  return true;
}

bool VkComposer::ensure_pipeline(std::int64_t format) {
  if (pipeline_ && pipeline_format_ == format) return true;
  if (pipeline_ && !finish()) return false;
  destroy_pipeline();
  const Vk& vk = *vk_;
  VkAttachmentDescription color{};
  color.format = static_cast<VkFormat>(format);
  color.samples = VK_SAMPLE_COUNT_1_BIT;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;  // every pixel is written
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  color.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  color.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  const VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &ref;
  // The runtime's earlier reads of the image (its compositor) before our writes.
  const VkSubpassDependency before{VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                                   VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0,
                                   VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, 0};
  VkRenderPassCreateInfo rpi{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO, nullptr, 0, 1, &color, 1, &subpass, 1, &before};
  if (vk.CreateRenderPass(device_, &rpi, nullptr, &render_pass_) != VK_SUCCESS) return false;

  VkPipelineShaderStageCreateInfo stages[2]{};
  stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT, vertex_,
               "main", nullptr};
  stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT, fragment_,
               "main", nullptr};
  VkPipelineVertexInputStateCreateInfo input{};
  input.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
  VkPipelineInputAssemblyStateCreateInfo assembly{};
  assembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{};
  viewport.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
  viewport.viewportCount = viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{};
  raster.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{};
  multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineColorBlendAttachmentState blend_attachment{};
  blend_attachment.colorWriteMask =
      VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  VkPipelineColorBlendStateCreateInfo blend{};
  blend.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
  blend.attachmentCount = 1;
  blend.pAttachments = &blend_attachment;
  const VkDynamicState dynamic_states[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO, nullptr, 0, 2,
                                           dynamic_states};
  VkGraphicsPipelineCreateInfo pi{};
  pi.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
  pi.stageCount = 2;
  pi.pStages = stages;
  pi.pVertexInputState = &input;
  pi.pInputAssemblyState = &assembly;
  pi.pViewportState = &viewport;
  pi.pRasterizationState = &raster;
  pi.pMultisampleState = &multisample;
  pi.pColorBlendState = &blend;
  pi.pDynamicState = &dynamic;
  pi.layout = pipeline_layout_;
  pi.renderPass = render_pass_;
  if (vk.CreateGraphicsPipelines(device_, VK_NULL_HANDLE, 1, &pi, nullptr, &pipeline_) != VK_SUCCESS) {
    destroy_pipeline();
    return false;
  }
  pipeline_format_ = format;
  return true;
}

bool VkComposer::compose(const ComposeSource& outer, const ComposeSource& inner, const ComposeTarget& target,
                         const TanRect& out, float blend_deg) {
  const Vk& vk = *vk_;
  if (target.w <= 0 || target.h <= 0 || !outer.image || !inner.image || !target.image) return false;
  Slot& slot = slots_[static_cast<std::size_t>(next_slot_)];
  if (!wait_slot(slot, kSecond)) return false;  // the GPU is a second behind: show the outer view, never hang
  if (!ensure_pipeline(target.format)) return false;
  CachedView* ov = view_of(outer.image, outer.serial, outer.format, outer.layer);
  CachedView* iv = ov ? view_of(inner.image, inner.serial, inner.format, inner.layer) : nullptr;
  CachedView* tv = iv ? view_of(target.image, target.serial, target.format) : nullptr;
  if (!tv || !framebuffer_of(*tv, target.w, target.h)) return false;
  next_slot_ = (next_slot_ + 1) % kSlots;

  VkDescriptorImageInfo images[2] = {{sampler_, ov->view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
                                     {sampler_, iv->view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
  VkWriteDescriptorSet writes[2]{};
  for (std::uint32_t i = 0; i < 2; ++i) {
    writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[i].dstSet = slot.set;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    writes[i].pImageInfo = &images[i];
  }
  vk.UpdateDescriptorSets(device_, 2, writes, 0, nullptr);

  Params p{};
  set_rect(p.out_tan, {out.left, out.right, out.up, out.down});  // rows run top-down
  set_rect(p.outer_tan, outer.fov);
  set_rect(p.inner_tan, inner.fov);
  set_uv(p.outer_uv, outer);
  set_uv(p.inner_uv, inner);
  p.out_size[0] = static_cast<float>(target.w);
  p.out_size[1] = static_cast<float>(target.h);
  p.band = blend_deg * 3.14159265f / 180.0f;

  VkCommandBuffer cb = slot.commands;
  vk.ResetCommandBuffer(cb, 0);
  const VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr,
                                       VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT, nullptr};
  if (vk.BeginCommandBuffer(cb, &begin) != VK_SUCCESS) return false;
  // The app's images (the layers sampled): from attachments (the app's draws, earlier on
  // this queue) to sampled, and back. One barrier when both views are in one layer.
  const VkImage sources[2] = {reinterpret_cast<VkImage>(outer.image), reinterpret_cast<VkImage>(inner.image)};
  const std::uint32_t layers[2] = {outer.layer, inner.layer};
  const std::uint32_t n_sources = sources[0] == sources[1] && layers[0] == layers[1] ? 1 : 2;
  VkImageMemoryBarrier to_read[2], to_attachment[2];
  for (std::uint32_t i = 0; i < n_sources; ++i) {
    to_read[i] = layout_barrier(sources[i], VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                                VK_ACCESS_SHADER_READ_BIT, layers[i]);
    to_attachment[i] = layout_barrier(sources[i], VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                      VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, 0,
                                      VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                                      layers[i]);
  }
  vk.CmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0, 0,
                        nullptr, 0, nullptr, n_sources, to_read);
  const VkRenderPassBeginInfo rb{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO, nullptr, render_pass_, tv->framebuffer,
                                 {{0, 0}, {static_cast<std::uint32_t>(target.w), static_cast<std::uint32_t>(target.h)}},
                                 0, nullptr};
  vk.CmdBeginRenderPass(cb, &rb, VK_SUBPASS_CONTENTS_INLINE);
  vk.CmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
  const VkViewport viewport{0, 0, static_cast<float>(target.w), static_cast<float>(target.h), 0, 1};
  vk.CmdSetViewport(cb, 0, 1, &viewport);
  vk.CmdSetScissor(cb, 0, 1, &rb.renderArea);
  vk.CmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout_, 0, 1, &slot.set, 0, nullptr);
  vk.CmdPushConstants(cb, pipeline_layout_, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof p, &p);
  vk.CmdDraw(cb, 3, 1, 0, 0);
  vk.CmdEndRenderPass(cb);
  vk.CmdPipelineBarrier(cb, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, 0,
                        nullptr, 0, nullptr, n_sources, to_attachment);
  if (vk.EndCommandBuffer(cb) != VK_SUCCESS) return false;
  vk.ResetFences(device_, 1, &slot.fence);
  VkSubmitInfo submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cb;
  if (vk.QueueSubmit(queue_, 1, &submit, slot.fence) != VK_SUCCESS) {
    // Signal-less fence would stall the slot forever: leave it signalled by an empty submit.
    vk.QueueSubmit(queue_, 0, nullptr, slot.fence);
    return false;
  }
  return true;
}

bool VkComposer::read(const ComposeTarget& target, std::vector<std::uint8_t>& rgba) {
  const bool bgra = target.format == VK_FORMAT_B8G8R8A8_UNORM || target.format == VK_FORMAT_B8G8R8A8_SRGB;
  if (!bgra && target.format != VK_FORMAT_R8G8B8A8_UNORM && target.format != VK_FORMAT_R8G8B8A8_SRGB) return false;
  if (!finish()) return false;
  const Vk& vk = *vk_;
  const VkDeviceSize size = static_cast<VkDeviceSize>(target.w) * static_cast<VkDeviceSize>(target.h) * 4;
  VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, nullptr, 0, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                        VK_SHARING_MODE_EXCLUSIVE, 0, nullptr};
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  if (vk.CreateBuffer(device_, &bi, nullptr, &buffer) != VK_SUCCESS) return false;
  VkMemoryRequirements req;
  vk.GetBufferMemoryRequirements(device_, buffer, &req);
  VkPhysicalDeviceMemoryProperties props;
  vk.GetPhysicalDeviceMemoryProperties(vk.physical, &props);
  constexpr VkMemoryPropertyFlags kHost = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  std::uint32_t type = props.memoryTypeCount;
  for (std::uint32_t i = 0; i < props.memoryTypeCount && type == props.memoryTypeCount; ++i)
    if ((req.memoryTypeBits & (1u << i)) && (props.memoryTypes[i].propertyFlags & kHost) == kHost) type = i;
  bool ok = type < props.memoryTypeCount;
  VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size, type};
  ok = ok && vk.AllocateMemory(device_, &mai, nullptr, &memory) == VK_SUCCESS &&
       vk.BindBufferMemory(device_, buffer, memory, 0) == VK_SUCCESS;
  Slot& slot = slots_[static_cast<std::size_t>(next_slot_)];
  VkCommandBuffer cb = slot.commands;
  const VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr,
                                       VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT, nullptr};
  ok = ok && vk.ResetCommandBuffer(cb, 0) == VK_SUCCESS && vk.BeginCommandBuffer(cb, &begin) == VK_SUCCESS;
  if (ok) {
    const VkImage image = reinterpret_cast<VkImage>(target.image);
    const VkImageMemoryBarrier to_copy = layout_barrier(image, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                                        VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                                        VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    const VkImageMemoryBarrier back = layout_barrier(image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, 0,
                                                     VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    vk.CmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
                          nullptr, 0, nullptr, 1, &to_copy);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {static_cast<std::uint32_t>(target.w), static_cast<std::uint32_t>(target.h), 1};
    vk.CmdCopyImageToBuffer(cb, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &region);
    vk.CmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, 0,
                          nullptr, 0, nullptr, 1, &back);
    VkSubmitInfo submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cb;
    vk.ResetFences(device_, 1, &slot.fence);
    ok = vk.EndCommandBuffer(cb) == VK_SUCCESS && vk.QueueSubmit(queue_, 1, &submit, slot.fence) == VK_SUCCESS;
    if (!ok) vk.QueueSubmit(queue_, 0, nullptr, slot.fence);  // keep the slot's fence signalled
    ok = ok && wait_slot(slot, 10 * kSecond);
  }
  void* mapped = nullptr;
  if (ok && vk.MapMemory(device_, memory, 0, size, 0, &mapped) == VK_SUCCESS) {
    rgba.resize(static_cast<std::size_t>(size));
    std::memcpy(rgba.data(), mapped, rgba.size());
    vk.UnmapMemory(device_, memory);
    if (bgra)
      for (std::size_t i = 0; i < rgba.size(); i += 4) std::swap(rgba[i], rgba[i + 2]);
  } else {
    ok = false;
  }
  vk.DestroyBuffer(device_, buffer, nullptr);
  if (memory) vk.FreeMemory(device_, memory, nullptr);
  return ok;
}

}  // namespace foveal::openxr

// Implements dstrans_vk.hpp.
#include "dstrans_vk.hpp"

#include <algorithm>
#include <cstring>
#include <iterator>

namespace dstrans::vk {

namespace {

std::uint64_t content_hash(const std::string& text, spirv::stage st) {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a
  for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  return (h ^ std::uint64_t(st)) * 1099511628211ull;
}

VkImageMemoryBarrier image_barrier(VkImage img, VkImageLayout from, VkImageLayout to, VkAccessFlags src,
                                   VkAccessFlags dst, VkImageAspectFlags aspect) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = src;
  b.dstAccessMask = dst;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = img;
  b.subresourceRange = {aspect, 0, VK_REMAINING_MIP_LEVELS, 0, VK_REMAINING_ARRAY_LAYERS};
  return b;
}

// Set 0 of a pipeline, from what its shaders declare.
result<VkDescriptorSetLayout> set_layout_from(const context& ctx, const std::vector<const shader*>& stages) {
  std::map<int, VkDescriptorSetLayoutBinding> bindings;
  int clash = -1;
  for (const shader* s : stages) {
    const VkShaderStageFlags flag = s->stage == spirv::stage::vertex     ? VK_SHADER_STAGE_VERTEX_BIT
                                    : s->stage == spirv::stage::fragment ? VK_SHADER_STAGE_FRAGMENT_BIT
                                                                         : VK_SHADER_STAGE_COMPUTE_BIT;
    auto add = [&](const std::vector<spirv::resource>& list, VkDescriptorType type) -> bool {
      for (const auto& r : list) {
        if (r.set != 0) return false;
        const bool seen = bindings.count(r.binding) > 0;
        auto& b = bindings[r.binding];
        if (seen && b.descriptorType != type) {
          clash = r.binding;
          return false;
        }
        b.binding = std::uint32_t(r.binding);
        b.descriptorType = type;
        b.descriptorCount = 1;
        b.stageFlags |= flag;
      }
      return true;
    };
    const auto& refl = s->reflection;
    if (!add(refl.samplers, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER) ||
        !add(refl.uniform_buffers, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER) ||
        !add(refl.storage_buffers, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER) ||
        !add(refl.storage_images, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE) ||
        !add(refl.texel_buffers, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER))
      return failure{clash >= 0 ? "binding " + std::to_string(clash) + " is declared as two kinds of resource"
                                : std::string("dstrans pipelines bind everything in descriptor set 0")};
  }
  std::vector<VkDescriptorSetLayoutBinding> list;
  for (auto& [binding, b] : bindings) list.push_back(b);
  VkDescriptorSetLayoutCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  ci.bindingCount = std::uint32_t(list.size());
  ci.pBindings = list.data();
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  if (vkCreateDescriptorSetLayout(ctx.device, &ci, ctx.allocator, &layout) != VK_SUCCESS)
    return failure{"cannot create a descriptor set layout"};
  return layout;
}

}  // namespace

result<std::unique_ptr<device>> device::create(const context& ctx) {
  if (!ctx.device || !ctx.physical_device || !ctx.queue) return failure{"dstrans::vk::context needs a device and a queue"};
  std::unique_ptr<device> d(new device(ctx));
  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pci.queueFamilyIndex = ctx.queue_family;
  if (vkCreateCommandPool(ctx.device, &pci, ctx.allocator, &d->pool_) != VK_SUCCESS)
    return failure{"cannot create a command pool"};
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = d->pool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  vkAllocateCommandBuffers(ctx.device, &ai, &d->cmd_);
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  vkCreateFence(ctx.device, &fci, ctx.allocator, &d->fence_);
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(ctx.physical_device, &props);
  d->timestamp_ns_ = double(props.limits.timestampPeriod);
  if (ctx.debug_utils)
    d->set_name_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
        vkGetInstanceProcAddr(ctx.instance, "vkSetDebugUtilsObjectNameEXT"));
  d->begin_rendering_ = reinterpret_cast<PFN_vkCmdBeginRendering>(vkGetDeviceProcAddr(ctx.device, "vkCmdBeginRendering"));
  d->end_rendering_ = reinterpret_cast<PFN_vkCmdEndRendering>(vkGetDeviceProcAddr(ctx.device, "vkCmdEndRendering"));
  if (!d->begin_rendering_) {
    d->begin_rendering_ = reinterpret_cast<PFN_vkCmdBeginRendering>(vkGetDeviceProcAddr(ctx.device, "vkCmdBeginRenderingKHR"));
    d->end_rendering_ = reinterpret_cast<PFN_vkCmdEndRendering>(vkGetDeviceProcAddr(ctx.device, "vkCmdEndRenderingKHR"));
  }
  d->set_cull_mode_ = reinterpret_cast<PFN_vkCmdSetCullMode>(vkGetDeviceProcAddr(ctx.device, "vkCmdSetCullMode"));
  if (!d->set_cull_mode_)
    d->set_cull_mode_ = reinterpret_cast<PFN_vkCmdSetCullMode>(vkGetDeviceProcAddr(ctx.device, "vkCmdSetCullModeEXT"));
  if (!d->begin_rendering_ || !d->end_rendering_)
    return failure{"the device has no dynamic rendering (Vulkan 1.3, or VK_KHR_dynamic_rendering on 1.2)"};
  d->name(VK_OBJECT_TYPE_COMMAND_POOL, std::uint64_t(d->pool_), "dstrans commands");
  return d;
}

device::~device() {
  for (auto& [n, p] : formula_pipelines_) destroy(p);
  for (auto& [h, s] : shaders_) vkDestroyShaderModule(ctx_.device, s->module, ctx_.allocator);
  if (timestamps_) vkDestroyQueryPool(ctx_.device, timestamps_, ctx_.allocator);
  if (fence_) vkDestroyFence(ctx_.device, fence_, ctx_.allocator);
  if (pool_) vkDestroyCommandPool(ctx_.device, pool_, ctx_.allocator);
  for (auto& [id, b] : blocks_) vkFreeMemory(ctx_.device, b.memory, ctx_.allocator);  // what was not destroyed
}

void device::name(VkObjectType type, std::uint64_t handle, const std::string& text) {
  if (!set_name_) return;
  VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = text.c_str();
  set_name_(ctx_.device, &info);
}

std::size_t device::memory_blocks() const { return blocks_.size(); }

result<allocation> device::take(const VkMemoryRequirements& req, VkMemoryPropertyFlags flags, bool linear) {
  auto type = memory_type(req.memoryTypeBits, flags);
  if (!type) return failure{type.error()};
  const VkDeviceSize align = std::max<VkDeviceSize>(req.alignment, 1);
  // First fit in a block of the same kind: a free range that holds the aligned slice.
  for (auto& [id, b] : blocks_) {
    if (b.type != *type || b.linear != linear) continue;
    for (auto it = b.free.begin(); it != b.free.end(); ++it) {
      const VkDeviceSize start = (it->first + align - 1) / align * align, end = it->first + it->second;
      if (start + req.size > end) continue;
      const VkDeviceSize before = start - it->first, after = end - (start + req.size), from = it->first;
      b.free.erase(it);
      if (before) b.free[from] = before;
      if (after) b.free[start + req.size] = after;
      return allocation{id, start, req.size};
    }
  }
  constexpr VkDeviceSize block_size = VkDeviceSize(64) << 20;
  memory_block b;
  b.type = *type;
  b.linear = linear;
  b.size = std::max(block_size, req.size);
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = b.size;
  ai.memoryTypeIndex = b.type;
  if (vkAllocateMemory(ctx_.device, &ai, ctx_.allocator, &b.memory) != VK_SUCCESS) return failure{"out of device memory"};
  if (flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) vkMapMemory(ctx_.device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped);
  if (req.size < b.size) b.free[req.size] = b.size - req.size;
  const std::uint32_t id = next_block_++;
  blocks_[id] = std::move(b);
  return allocation{id, 0, req.size};
}

void device::release(allocation& a) {
  const auto it = blocks_.find(a.block);
  if (it == blocks_.end()) return;
  memory_block& b = it->second;
  VkDeviceSize offset = a.offset, size = a.size;
  // Coalesce with the free ranges on either side.
  auto next = b.free.lower_bound(offset);
  if (next != b.free.end() && next->first == offset + size) {
    size += next->second;
    next = b.free.erase(next);
  }
  if (next != b.free.begin()) {
    auto prev = std::prev(next);
    if (prev->first + prev->second == offset) {
      offset = prev->first;
      size += prev->second;
      b.free.erase(prev);
    }
  }
  b.free[offset] = size;
  if (offset == 0 && size == b.size) {
    vkFreeMemory(ctx_.device, b.memory, ctx_.allocator);
    blocks_.erase(it);
  }
  a = allocation{};
}

result<std::uint32_t> device::memory_type(std::uint32_t bits, VkMemoryPropertyFlags flags) const {
  VkPhysicalDeviceMemoryProperties mp;
  vkGetPhysicalDeviceMemoryProperties(ctx_.physical_device, &mp);
  for (std::uint32_t i = 0; i < mp.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & flags) == flags) return i;
  return failure{"no suitable memory type"};
}

result<image> device::make_image(VkFormat fmt, VkImageUsageFlags usage, VkImageAspectFlags aspect, int w, int h,
                                 const std::string& label, VkImageViewType view_type, int depth_or_layers, int levels) {
  image img;
  img.format = fmt;
  const bool volume = view_type == VK_IMAGE_VIEW_TYPE_3D, layered = view_type == VK_IMAGE_VIEW_TYPE_2D_ARRAY;
  VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ci.imageType = volume ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
  ci.format = fmt;
  ci.extent = {std::uint32_t(w), std::uint32_t(h), volume ? std::uint32_t(depth_or_layers) : 1u};
  ci.mipLevels = std::uint32_t(levels);
  ci.arrayLayers = layered ? std::uint32_t(depth_or_layers) : 1u;
  ci.samples = VK_SAMPLE_COUNT_1_BIT;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage = usage;
  ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  if (vkCreateImage(ctx_.device, &ci, ctx_.allocator, &img.handle) != VK_SUCCESS) return failure{label + ": cannot create the image"};
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(ctx_.device, img.handle, &req);
  auto slice = take(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, false);
  if (!slice) {
    destroy(img);
    return failure{label + ": cannot allocate the image's memory (" + slice.error() + ")"};
  }
  img.slice = *slice;
  img.memory = blocks_.at(slice->block).memory;
  vkBindImageMemory(ctx_.device, img.handle, img.memory, slice->offset);
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = img.handle;
  vi.viewType = view_type;
  vi.format = fmt;
  vi.subresourceRange = {aspect, 0, ci.mipLevels, 0, ci.arrayLayers};
  vkCreateImageView(ctx_.device, &vi, ctx_.allocator, &img.view);
  name(VK_OBJECT_TYPE_IMAGE, std::uint64_t(img.handle), label);
  name(VK_OBJECT_TYPE_IMAGE_VIEW, std::uint64_t(img.view), label);
  return img;
}

void device::destroy(image& i) {
  if (i.view) vkDestroyImageView(ctx_.device, i.view, ctx_.allocator);
  if (i.handle) vkDestroyImage(ctx_.device, i.handle, ctx_.allocator);
  release(i.slice);
  i = image{};
}

result<targets> device::make_targets(const std::vector<target_desc>& layout, int width, int height,
                                     const std::string& label, bool with_depth) {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(ctx_.physical_device, &props);
  const int max_size = int(props.limits.maxImageDimension2D);
  if (width < 1 || height < 1 || width > max_size || height > max_size)
    return failure{label + ": " + std::to_string(width) + "x" + std::to_string(height) +
                   " is not a size this device can render (1 to " + std::to_string(max_size) + " a side)"};
  if (layout.size() > props.limits.maxColorAttachments)
    return failure{label + ": the layout has " + std::to_string(layout.size()) + " render targets; this device draws to at most " +
                   std::to_string(props.limits.maxColorAttachments)};
  const VkFormatFeatureFlags need = VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
  for (const target_desc& d : layout) {
    VkFormatProperties fp;
    vkGetPhysicalDeviceFormatProperties(ctx_.physical_device, VkFormat(info(d.fmt).vk_format), &fp);
    if ((fp.optimalTilingFeatures & need) != need)
      return failure{label + ": this device cannot render to " + info(d.fmt).name + " targets"};
  }
  targets t;
  t.width = width;
  t.height = height;
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                  VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  for (std::size_t i = 0; i < layout.size(); ++i) {
    auto img = make_image(VkFormat(info(layout[i].fmt).vk_format), usage, VK_IMAGE_ASPECT_COLOR_BIT, width, height,
                          label + " RT" + std::to_string(i) + " " + info(layout[i].fmt).name);
    if (!img) {
      destroy(t);
      return failure{img.error()};
    }
    t.colors.push_back(*img);
    t.formats.push_back(layout[i].fmt);
  }
  if (with_depth) {
    auto img = make_image(VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                          VK_IMAGE_ASPECT_DEPTH_BIT, width, height, label + " depth");
    if (!img) {
      destroy(t);
      return failure{img.error()};
    }
    t.depth = *img;
  }
  submit([&](VkCommandBuffer cmd) {
    std::vector<VkImageMemoryBarrier> barriers;
    for (const image& c : t.colors)
      barriers.push_back(image_barrier(c.handle, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, 0,
                                       VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_IMAGE_ASPECT_COLOR_BIT));
    if (t.depth.handle)
      barriers.push_back(image_barrier(t.depth.handle, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, 0,
                                       VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_IMAGE_ASPECT_DEPTH_BIT));
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0,
                         nullptr, std::uint32_t(barriers.size()), barriers.data());
  });
  return t;
}

result<image> device::make_storage_image(VkFormat fmt, int width, int height, const std::string& label) {
  auto img = make_image(fmt, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                        VK_IMAGE_ASPECT_COLOR_BIT, width, height, label);
  if (!img) return img;
  submit([&](VkCommandBuffer cmd) {
    const VkImageMemoryBarrier b = image_barrier(img->handle, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, 0,
                                                 VK_ACCESS_SHADER_WRITE_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &b);
  });
  return img;
}

result<image> device::make_sampled_image(VkFormat fmt, VkImageViewType view_type, int width, int height,
                                         int depth_or_layers, const std::string& label, bool storage) {
  VkFormatFeatureFlags wanted = VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
  if (view_type == VK_IMAGE_VIEW_TYPE_3D) wanted |= VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
  if (storage) wanted |= VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT;
  VkFormatProperties props;
  vkGetPhysicalDeviceFormatProperties(ctx_.physical_device, fmt, &props);
  if ((props.optimalTilingFeatures & wanted) != wanted)
    return failure{label + ": the device cannot sample (and filter, a 3D image; store to, a storage one) format " + std::to_string(int(fmt))};
  if (width < 1 || height < 1 || depth_or_layers < 1) return failure{label + ": an image needs at least one texel"};
  const VkImageUsageFlags use = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                (storage ? VkImageUsageFlags(VK_IMAGE_USAGE_STORAGE_BIT) : VkImageUsageFlags(0));
  auto img = make_image(fmt, use, VK_IMAGE_ASPECT_COLOR_BIT, width, height, label, view_type, depth_or_layers);
  if (!img) return img;
  submit([&](VkCommandBuffer cmd) {
    const VkImageMemoryBarrier b = image_barrier(img->handle, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, 0,
                                                 VK_ACCESS_TRANSFER_WRITE_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &b);
  });
  return img;
}

result<image> device::make_texture_array(const texture_array& a, const std::string& label) {
  const VkFormat fmt = VK_FORMAT_R8G8B8A8_UNORM;
  const VkImageUsageFlags use = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  VkImageFormatProperties limits{};
  if (vkGetPhysicalDeviceImageFormatProperties(ctx_.physical_device, fmt, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL, use, 0, &limits) != VK_SUCCESS ||
      std::uint32_t(a.layers) > limits.maxArrayLayers || std::uint32_t(a.width) > limits.maxExtent.width ||
      std::uint32_t(a.height) > limits.maxExtent.height || std::uint32_t(a.levels.size()) > limits.maxMipLevels)
    return failure{label + ": " + std::to_string(a.layers) + " layers of " + std::to_string(a.width) + " x " + std::to_string(a.height) +
                   " RGBA8 texels exceed the device's array images (" + std::to_string(limits.maxArrayLayers) + " layers of " +
                   std::to_string(limits.maxExtent.width) + ")"};
  std::size_t total = 0;
  for (const std::vector<std::uint8_t>& level : a.levels) total += level.size();
  auto staging = make_buffer(VkDeviceSize(total), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, label + " upload");
  if (!staging) return failure{staging.error()};
  auto img = make_image(fmt, use, VK_IMAGE_ASPECT_COLOR_BIT, a.width, a.height, label, VK_IMAGE_VIEW_TYPE_2D_ARRAY, a.layers, int(a.levels.size()));
  if (!img) {
    destroy(*staging);
    return img;
  }
  std::vector<VkBufferImageCopy> copies;
  VkDeviceSize offset = 0;
  for (std::size_t l = 0; l < a.levels.size(); ++l) {
    std::memcpy(static_cast<std::uint8_t*>(staging->mapped) + offset, a.levels[l].data(), a.levels[l].size());
    const glm::ivec2 size = a.level_size(int(l));
    VkBufferImageCopy c{};
    c.bufferOffset = offset;
    c.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, std::uint32_t(l), 0, std::uint32_t(a.layers)};
    c.imageExtent = {std::uint32_t(size.x), std::uint32_t(size.y), 1u};
    copies.push_back(c);
    offset += VkDeviceSize(a.levels[l].size());
  }
  submit([&](VkCommandBuffer cmd) {
    const VkImageMemoryBarrier into = image_barrier(img->handle, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                                                    VK_ACCESS_TRANSFER_WRITE_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &into);
    vkCmdCopyBufferToImage(cmd, staging->handle, img->handle, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, std::uint32_t(copies.size()), copies.data());
    const VkImageMemoryBarrier after = image_barrier(img->handle, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
                                                     VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0, nullptr, 1, &after);
  });
  destroy(*staging);
  return img;
}

void device::destroy(targets& t) {
  for (image& c : t.colors) destroy(c);
  destroy(t.depth);
  t = targets{};
}

result<std::vector<std::uint8_t>> device::read_image(VkImage img, std::size_t bytes_per_pixel, int width, int height,
                                                    VkImageLayout current, int depth) {
  const std::size_t n = std::size_t(width) * std::size_t(height) * std::size_t(depth) * bytes_per_pixel;
  auto staging = make_buffer(VkDeviceSize(n), VK_BUFFER_USAGE_TRANSFER_DST_BIT, "dstrans readback");
  if (!staging) return failure{staging.error()};
  submit([&](VkCommandBuffer cmd) {
    // Copies want TRANSFER_SRC_OPTIMAL; the image returns to the layout it was in.
    VkImageMemoryBarrier before = image_barrier(img, current, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                                VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_SHADER_WRITE_BIT,
                                                VK_ACCESS_TRANSFER_READ_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr,
                         1, &before);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {std::uint32_t(width), std::uint32_t(height), std::uint32_t(depth)};
    vkCmdCopyImageToBuffer(cmd, img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging->handle, 1, &region);
    VkImageMemoryBarrier after = image_barrier(img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, current,
                                               VK_ACCESS_TRANSFER_READ_BIT, 0, VK_IMAGE_ASPECT_COLOR_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0, nullptr,
                         1, &after);
    VkBufferMemoryBarrier to_host{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
    to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    to_host.srcQueueFamilyIndex = to_host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_host.buffer = staging->handle;
    to_host.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &to_host, 0,
                         nullptr);
  });
  const auto* bytes = static_cast<const std::uint8_t*>(staging->mapped);
  std::vector<std::uint8_t> out(bytes, bytes + n);
  destroy(*staging);
  return out;
}

result<std::vector<texel>> device::read_texels(const targets& t, int index, VkImageLayout current) {
  const std::size_t bpp = std::size_t(info(t.formats[std::size_t(index)]).bytes_per_pixel);
  auto bytes = read_image(t.colors[std::size_t(index)].handle, bpp, t.width, t.height, current);
  if (!bytes) return failure{bytes.error()};
  std::vector<texel> out(std::size_t(t.width) * std::size_t(t.height));
  for (std::size_t i = 0; i < out.size(); ++i) std::memcpy(out[i].data(), bytes->data() + i * bpp, bpp);
  return out;
}

result<std::vector<std::uint32_t>> device::read_words(const image& img, int width, int height) {
  auto bytes = read_image(img.handle, 4, width, height, VK_IMAGE_LAYOUT_GENERAL);
  if (!bytes) return failure{bytes.error()};
  std::vector<std::uint32_t> out(bytes->size() / 4);
  std::memcpy(out.data(), bytes->data(), bytes->size());
  return out;
}

result<std::vector<std::uint8_t>> device::read_volume(const image& img, std::size_t bytes_per_texel, glm::ivec3 size, VkImageLayout current) {
  return read_image(img.handle, bytes_per_texel, size.x, size.y, current, size.z);
}

result<buffer> device::make_buffer(VkDeviceSize size, VkBufferUsageFlags usage, const std::string& label) {
  buffer b;
  b.size = size;
  VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  ci.size = size ? size : 4;
  ci.usage = usage;
  if (vkCreateBuffer(ctx_.device, &ci, ctx_.allocator, &b.handle) != VK_SUCCESS) return failure{label + ": cannot create the buffer"};
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx_.device, b.handle, &req);
  auto slice = take(req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, true);
  if (!slice) {
    destroy(b);
    return failure{label + ": cannot allocate host-visible memory (" + slice.error() + ")"};
  }
  b.slice = *slice;
  const memory_block& block = blocks_.at(slice->block);
  b.memory = block.memory;
  b.mapped = static_cast<char*>(block.mapped) + slice->offset;
  vkBindBufferMemory(ctx_.device, b.handle, b.memory, slice->offset);
  name(VK_OBJECT_TYPE_BUFFER, std::uint64_t(b.handle), label);
  return b;
}

void device::destroy(buffer& b) {
  if (b.handle) vkDestroyBuffer(ctx_.device, b.handle, ctx_.allocator);
  release(b.slice);
  b = buffer{};
}

result<const shader*> device::get_shader(const glsl::source& src, spirv::stage st, const std::string& label) {
  const std::uint64_t key = content_hash(src.str(), st);
  const auto it = shaders_.find(key);
  if (it != shaders_.end()) return static_cast<const shader*>(it->second.get());
  auto words = spirv::compile(src, st, spirv::api::vulkan);
  if (!words) return failure{label + ": " + words.error()};
  auto refl = spirv::reflect(*words);
  if (!refl) return failure{label + ": " + refl.error()};
  auto s = std::make_unique<shader>();
  s->stage = st;
  s->reflection = *refl;
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = words->size() * 4;
  ci.pCode = words->data();
  if (vkCreateShaderModule(ctx_.device, &ci, ctx_.allocator, &s->module) != VK_SUCCESS)
    return failure{label + ": cannot create the shader module"};
  name(VK_OBJECT_TYPE_SHADER_MODULE, std::uint64_t(s->module), label);
  const shader* out = s.get();
  shaders_.emplace(key, std::move(s));
  return out;
}

result<pipeline> device::pipeline_layout(const std::vector<const shader*>& stages, const std::string& label) {
  auto set_layout = set_layout_from(ctx_, stages);
  if (!set_layout) return failure{label + ": " + set_layout.error()};
  pipeline p;
  p.set_layout = *set_layout;
  VkPipelineLayoutCreateInfo lci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  lci.setLayoutCount = 1;
  lci.pSetLayouts = &p.set_layout;
  vkCreatePipelineLayout(ctx_.device, &lci, ctx_.allocator, &p.layout);
  return p;
}

result<pipeline> device::make_graphics_pipeline(const shader& vertex, const shader& fragment,
                                                const std::vector<format>& color_formats, const std::string& label,
                                                const pipeline_state& state) {
  // The fragment shader must write exactly the targets it is drawn into.
  const auto& outs = fragment.reflection.outputs;
  if (outs.size() != color_formats.size())
    return failure{label + ": the fragment shader writes " + std::to_string(outs.size()) + " outputs but the pipeline draws into " +
                   std::to_string(color_formats.size()) + " targets"};
  for (std::size_t i = 0; i < outs.size(); ++i) {
    if (outs[i].location != int(i) || outs[i].components != info(color_formats[i]).channels)
      return failure{label + ": output '" + outs[i].name + "' (location " + std::to_string(outs[i].location) + ", " +
                     std::to_string(outs[i].components) + " components) does not match target " + std::to_string(i) + " (" +
                     info(color_formats[i]).name + ")"};
  }
  auto laid_out = pipeline_layout({&vertex, &fragment}, label);
  if (!laid_out) return laid_out;
  pipeline p = *laid_out;

  VkPipelineShaderStageCreateInfo stages[2]{};
  for (int i = 0; i < 2; ++i) {
    stages[i].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    stages[i].pName = "main";
  }
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vertex.module;
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fragment.module;
  VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vertex_input.vertexBindingDescriptionCount = std::uint32_t(state.bindings.size());
  vertex_input.pVertexBindingDescriptions = state.bindings.data();
  vertex_input.vertexAttributeDescriptionCount = std::uint32_t(state.attributes.size());
  vertex_input.pVertexAttributeDescriptions = state.attributes.data();
  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = state.cull;
  raster.depthClampEnable = state.depth_clamp;
  // Counter-clockwise in clip space faces the viewer, as on GL; Vulkan's facing already accounts for
  // the negative-height viewport (tested: backend_vk_test.cpp, "clip-space +y is the image's top row").
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth.depthTestEnable = state.depth_test;
  depth.depthWriteEnable = state.depth_write;
  depth.depthCompareOp = state.depth_compare;
  std::vector<VkPipelineColorBlendAttachmentState> blends(color_formats.size());
  for (auto& b : blends) {
    b.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    if (state.additive) {
      b.blendEnable = VK_TRUE;
      b.srcColorBlendFactor = b.dstColorBlendFactor = b.srcAlphaBlendFactor = b.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
      b.colorBlendOp = b.alphaBlendOp = VK_BLEND_OP_ADD;
    }
    if (state.transmit) {
      b.blendEnable = VK_TRUE;
      b.srcColorBlendFactor = VK_BLEND_FACTOR_ONE;
      b.dstColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
      b.srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO;
      b.dstAlphaBlendFactor = state.transmit_alpha ? VK_BLEND_FACTOR_SRC_ALPHA : VK_BLEND_FACTOR_ONE;
      b.colorBlendOp = b.alphaBlendOp = VK_BLEND_OP_ADD;
    }
  }
  VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = std::uint32_t(blends.size());
  blend.pAttachments = blends.data();
  const VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR, VK_DYNAMIC_STATE_CULL_MODE};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = state.dynamic_cull && set_cull_mode_ ? 3 : 2;
  dynamic.pDynamicStates = dynamic_states;
  std::vector<VkFormat> formats;
  for (format f : color_formats) formats.push_back(VkFormat(info(f).vk_format));
  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = std::uint32_t(formats.size());
  rendering.pColorAttachmentFormats = formats.data();
  if (state.depth_attachment) rendering.depthAttachmentFormat = VK_FORMAT_D32_SFLOAT;

  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  ci.pNext = &rendering;
  ci.stageCount = 2;
  ci.pStages = stages;
  ci.pVertexInputState = &vertex_input;
  ci.pInputAssemblyState = &assembly;
  ci.pViewportState = &viewport;
  ci.pRasterizationState = &raster;
  ci.pMultisampleState = &multisample;
  ci.pDepthStencilState = &depth;
  ci.pColorBlendState = &blend;
  ci.pDynamicState = &dynamic;
  ci.layout = p.layout;
  if (vkCreateGraphicsPipelines(ctx_.device, VK_NULL_HANDLE, 1, &ci, ctx_.allocator, &p.handle) != VK_SUCCESS) {
    destroy(p);
    return failure{label + ": cannot create the graphics pipeline"};
  }
  name(VK_OBJECT_TYPE_PIPELINE, std::uint64_t(p.handle), label);
  return p;
}

result<pipeline> device::make_compute_pipeline(const shader& compute, const std::string& label) {
  auto laid_out = pipeline_layout({&compute}, label);
  if (!laid_out) return laid_out;
  pipeline p = *laid_out;
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  ci.stage.module = compute.module;
  ci.stage.pName = "main";
  ci.layout = p.layout;
  if (vkCreateComputePipelines(ctx_.device, VK_NULL_HANDLE, 1, &ci, ctx_.allocator, &p.handle) != VK_SUCCESS) {
    destroy(p);
    return failure{label + ": cannot create the compute pipeline"};
  }
  name(VK_OBJECT_TYPE_PIPELINE, std::uint64_t(p.handle), label);
  return p;
}

void device::destroy(pipeline& p) {
  if (p.handle) vkDestroyPipeline(ctx_.device, p.handle, ctx_.allocator);
  if (p.layout) vkDestroyPipelineLayout(ctx_.device, p.layout, ctx_.allocator);
  if (p.set_layout) vkDestroyDescriptorSetLayout(ctx_.device, p.set_layout, ctx_.allocator);
  p = pipeline{};
}

double device::submit(const std::function<void(VkCommandBuffer)>& record) {
  begin_passes(1);
  record_pass(record);
  return (*submit_passes())[0];
}

VkCommandBuffer device::begin_passes(std::size_t max_passes) {
  // Two timestamps a pass and two for the whole submission; the pool grows between submissions.
  const std::uint32_t needed = std::uint32_t(2 * max_passes + 2);
  if (needed > timestamp_capacity_) {
    if (timestamps_) vkDestroyQueryPool(ctx_.device, timestamps_, ctx_.allocator);
    VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    qci.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qci.queryCount = needed;
    vkCreateQueryPool(ctx_.device, &qci, ctx_.allocator, &timestamps_);
    name(VK_OBJECT_TYPE_QUERY_POOL, std::uint64_t(timestamps_), "dstrans timestamps");
    timestamp_capacity_ = needed;
  }
  passes_ = 0;
  max_passes_ = max_passes;
  vkResetCommandBuffer(cmd_, 0);
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(cmd_, &bi);
  vkCmdResetQueryPool(cmd_, timestamps_, 0, needed);
  vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps_, 0);
  return cmd_;
}

void device::record_pass(const std::function<void(VkCommandBuffer)>& record) {
  if (passes_ < max_passes_)
    vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps_, std::uint32_t(2 + 2 * passes_));
  record(cmd_);
  if (passes_ < max_passes_)
    vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps_, std::uint32_t(3 + 2 * passes_));
  ++passes_;
}

result<std::vector<double>> device::submit_passes() {
  vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps_, 1);
  vkEndCommandBuffer(cmd_);
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd_;
  vkQueueSubmit(ctx_.queue, 1, &si, fence_);
  vkWaitForFences(ctx_.device, 1, &fence_, VK_TRUE, UINT64_MAX);
  vkResetFences(ctx_.device, 1, &fence_);
  if (passes_ > max_passes_)
    return failure{std::to_string(passes_) + " passes were recorded into a submission begun for " +
                   std::to_string(max_passes_)};
  std::vector<std::uint64_t> ticks(2 + 2 * passes_);
  vkGetQueryPoolResults(ctx_.device, timestamps_, 0, std::uint32_t(ticks.size()), ticks.size() * sizeof ticks[0],
                        ticks.data(), sizeof ticks[0], VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
  auto ms = [&](std::uint64_t from, std::uint64_t to) { return double(to - from) * timestamp_ns_ * 1e-6; };
  std::vector<double> out;
  for (std::size_t k = 0; k < passes_; ++k) out.push_back(ms(ticks[2 + 2 * k], ticks[3 + 2 * k]));
  out.push_back(ms(ticks[0], ticks[1]));
  return out;
}

bool device::set_cull_mode(VkCommandBuffer cmd, VkCullModeFlags mode) const {
  if (!set_cull_mode_) return false;
  set_cull_mode_(cmd, mode);
  return true;
}

void device::begin_rendering(VkCommandBuffer cmd, const targets& t, const std::vector<glm::vec4>& clear, bool optimal) {
  std::vector<VkRenderingAttachmentInfo> colors;
  for (std::size_t i = 0; i < t.colors.size(); ++i) {
    VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    a.imageView = t.colors[i].view;
    a.imageLayout = optimal ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_GENERAL;
    a.loadOp = i < clear.size() ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    if (i < clear.size())
      for (int k = 0; k < 4; ++k) a.clearValue.color.float32[k] = clear[i][k];
    colors.push_back(a);
  }
  VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depth.imageView = t.depth.view;
  depth.imageLayout = optimal ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_GENERAL;
  depth.loadOp = clear.empty() ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  depth.clearValue.depthStencil = {1.0f, 0};
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, {std::uint32_t(t.width), std::uint32_t(t.height)}};
  ri.layerCount = 1;
  ri.colorAttachmentCount = std::uint32_t(colors.size());
  ri.pColorAttachments = colors.data();
  ri.pDepthAttachment = t.depth.view ? &depth : nullptr;
  begin_rendering_(cmd, &ri);
  set_area(cmd, glm::ivec4(0, 0, t.width, t.height));
}

void device::set_area(VkCommandBuffer cmd, glm::ivec4 area) {
  const VkViewport vp{float(area.x), float(area.y + area.w), float(area.z), -float(area.w), 0.0f, 1.0f};
  vkCmdSetViewport(cmd, 0, 1, &vp);
  const VkRect2D scissor{{area.x, area.y}, {std::uint32_t(area.z), std::uint32_t(area.w)}};
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void device::end_rendering(VkCommandBuffer cmd) { end_rendering_(cmd); }

result<words> device::run_formula(const formula& f, const words& args, std::size_t calls) {
  auto it = formula_pipelines_.find(f.name);
  if (it == formula_pipelines_.end()) {
    glsl::source src;
    glsl::add_formula_kernel(src, f);
    auto cs = get_shader(src, spirv::stage::compute, "dstrans eval " + f.name);
    if (!cs) return failure{cs.error()};
    auto p = make_compute_pipeline(**cs, "dstrans eval " + f.name);
    if (!p) return failure{p.error()};
    it = formula_pipelines_.emplace(f.name, *p).first;
  }
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(ctx_.physical_device, &props);
  return glsl::run_in_dispatches(f, args, calls, props.limits.maxComputeWorkGroupCount[0], props.limits.maxStorageBufferRange,
                                 [&](const words& part, std::size_t n) { return run_dispatch(it->second, f, part, n); });
}

result<words> device::run_dispatch(const pipeline& p, const formula& f, const words& args, std::size_t calls) {
  const std::size_t out_words = calls * std::size_t(f.result.word_count());
  auto in = make_buffer(VkDeviceSize((args.size() + 1) * 4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "dstrans eval in");
  auto out = make_buffer(VkDeviceSize((out_words ? out_words : 1) * 4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "dstrans eval out");
  if (!in || !out) return failure{in ? out.error() : in.error()};
  auto* in_words = static_cast<std::uint32_t*>(in->mapped);
  in_words[0] = std::uint32_t(calls);
  if (!args.empty()) std::memcpy(in_words + 1, args.data(), args.size() * 4);

  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2};
  VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pci.maxSets = 1;
  pci.poolSizeCount = 1;
  pci.pPoolSizes = &size;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  vkCreateDescriptorPool(ctx_.device, &pci, ctx_.allocator, &pool);
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &p.set_layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  vkAllocateDescriptorSets(ctx_.device, &ai, &set);
  VkDescriptorBufferInfo infos[2] = {{in->handle, 0, VK_WHOLE_SIZE}, {out->handle, 0, VK_WHOLE_SIZE}};
  VkWriteDescriptorSet writes[2]{};
  for (std::uint32_t i = 0; i < 2; ++i) {
    writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[i].dstSet = set;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(ctx_.device, 2, writes, 0, nullptr);
  submit([&](VkCommandBuffer cmd) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.handle);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout, 0, 1, &set, 0, nullptr);
    vkCmdDispatch(cmd, std::uint32_t((calls + 63) / 64), 1, 1);
    VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    to_host.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, nullptr,
                         0, nullptr);
  });
  words result_words(out_words);
  if (out_words) std::memcpy(result_words.data(), out->mapped, out_words * 4);
  vkDestroyDescriptorPool(ctx_.device, pool, ctx_.allocator);
  destroy(*in);
  destroy(*out);
  return result_words;
}

}  // namespace dstrans::vk

// dstrans on Vulkan 1.2+ (dynamic rendering: core in 1.3, VK_KHR_dynamic_rendering in 1.2): the part an
// engine copies unmodified (dstrans_vk.{hpp,cpp}, with backends/spirv/dstrans_spirv.{hpp,cpp}).
//
// Implements, on the engine's instance, device and queue (dstrans::vk::context):
//   - images for a layout's targets (make_targets), read back as bytes (read_texels); storage images
//     (make_storage_image), sampled 3D and array images (make_sampled_image) and mapped buffers (make_buffer);
//   - GLSL compiled to SPIR-V at run time by glslang, cached by content hash (get_shader);
//   - graphics and compute pipelines whose descriptor layouts come from SPIRV-Cross reflection, checked
//     against the layout the pipeline draws into before it is built (make_graphics_pipeline, make_compute_pipeline);
//   - one-shot command submission with GPU timestamps (submit), many timed passes in one submission
//     (begin_passes, record_pass, submit_passes), debug names (name);
//   - evaluation of a shared formula over many inputs in a compute shader (run_formula).
//
//   auto dev = dstrans::vk::device::create(ctx);   // ctx: the engine's VkInstance, VkDevice, queue, allocator
//   auto gbuf = (*dev)->make_targets(dstrans::describe<dstrans::thesis_gbuffer>(), w, h, "gbuffer", true);
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <dstrans/formula.hpp>
#include <dstrans/glsl.hpp>
#include <dstrans/layout.hpp>
#include <dstrans/material_textures.hpp>
#include <dstrans/result.hpp>
#include <dstrans_spirv.hpp>

namespace dstrans::vk {

// The engine's Vulkan objects dstrans works with; the engine keeps ownership of all of them.
struct context {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  std::uint32_t queue_family = 0;
  const VkAllocationCallbacks* allocator = nullptr;
  bool debug_utils = false;  // VK_EXT_debug_utils is enabled on the instance: dstrans names its objects
};

// Where an image's or a buffer's memory lies: a slice of one of the device's blocks (block 0: none).
struct allocation {
  std::uint32_t block = 0;
  VkDeviceSize offset = 0, size = 0;
};

struct image {
  VkImage handle = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;  // the block it lies in
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  allocation slice;
};

// One image per layout target (usable as colour attachment, sampled image and copy source), an optional
// D32 depth image, all in VK_IMAGE_LAYOUT_GENERAL after creation.
struct targets {
  std::vector<image> colors;
  std::vector<format> formats;
  image depth;
  int width = 0, height = 0;
};

// A host-visible, coherent, persistently mapped buffer.
struct buffer {
  VkBuffer handle = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;  // the block it lies in
  VkDeviceSize size = 0;
  void* mapped = nullptr;
  allocation slice;
};

struct shader {
  VkShaderModule module = VK_NULL_HANDLE;
  spirv::stage stage = spirv::stage::fragment;
  spirv::reflection reflection;
};

// How a graphics pipeline reads vertices and treats depth, blending and faces.
struct pipeline_state {
  std::vector<VkVertexInputBindingDescription> bindings;
  std::vector<VkVertexInputAttributeDescription> attributes;
  bool depth_attachment = false;  // a D32_SFLOAT depth attachment is bound
  bool depth_test = false, depth_write = false;
  VkCompareOp depth_compare = VK_COMPARE_OP_LESS;
  bool additive = false;  // blend ONE + ONE into every target
  // Blend colour = source + destination * source alpha, keeping the destination's alpha: the source is a
  // premultiplied layer whose alpha is the share of the image behind it that shows through.
  bool transmit = false;
  // With transmit, the destination's alpha multiplied by the source's instead (blending::layer): a layer
  // cleared to (0, 0, 0, 1) ends holding what it keeps of what lies behind it.
  bool transmit_alpha = false;
  VkCullModeFlags cull = VK_CULL_MODE_NONE;  // counter-clockwise faces are front faces
  // The cull mode is set while recording (device::set_cull_mode), where the device can; `cull` otherwise.
  bool dynamic_cull = false;
  // Depth clamped instead of clipping at the near and far planes (needs the device feature depthClamp).
  bool depth_clamp = false;
};

// A pipeline with the set-0 descriptor layout its shaders declare.
struct pipeline {
  VkPipeline handle = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
};

class device {
 public:
  // dstrans's objects on the engine's device: a command pool, a fence, a shader cache, and the memory
  // blocks its images and buffers are slices of (64 MiB each, or one for a larger resource; images and
  // buffers in blocks of their own, so that no slice needs bufferImageGranularity's padding; a block is
  // freed when its last slice is).
  static result<std::unique_ptr<device>> create(const context& ctx);
  ~device();
  device(const device&) = delete;
  device& operator=(const device&) = delete;

  const context& ctx() const { return ctx_; }

  // Images for `layout`; a failure names what the device cannot hold (too many targets, a format it
  // cannot render to, a zero or oversized extent).
  result<targets> make_targets(const std::vector<target_desc>& layout, int width, int height, const std::string& label,
                               bool with_depth);
  void destroy(targets& t);
  // The bytes of target `index`, row by row from the top of the image, which is in layout `current` and
  // returns to it (a renderer leaves its targets in SHADER_READ_ONLY_OPTIMAL).
  result<std::vector<texel>> read_texels(const targets& t, int index, VkImageLayout current = VK_IMAGE_LAYOUT_GENERAL);

  result<buffer> make_buffer(VkDeviceSize size, VkBufferUsageFlags usage, const std::string& label);
  void destroy(buffer& b);
  // A storage image (read and written by shaders, cleared and copied by transfers), in GENERAL layout.
  result<image> make_storage_image(VkFormat fmt, int width, int height, const std::string& label);
  // An image shaders sample and transfers fill (a 3D texture: VK_IMAGE_VIEW_TYPE_3D, filtered linearly, or
  // a 2D array: VK_IMAGE_VIEW_TYPE_2D_ARRAY), with `storage` also a storage image, in GENERAL layout; a
  // failure if the device cannot.
  result<image> make_sampled_image(VkFormat fmt, VkImageViewType view_type, int width, int height, int depth_or_layers,
                                   const std::string& label, bool storage = false);
  // The material textures `a` as an RGBA8 2D array image with its mip levels, filled, in GENERAL layout; a
  // failure past the device's limits for such images.
  result<image> make_texture_array(const texture_array& a, const std::string& label);
  // The 32-bit texels of a storage image such as an R32_UINT one, row by row from the top.
  result<std::vector<std::uint32_t>> read_words(const image& img, int width, int height);
  // The bytes of a 3D image of `size` texels, `bytes_per_texel` each, x fastest, from layout `current`.
  result<std::vector<std::uint8_t>> read_volume(const image& img, std::size_t bytes_per_texel, glm::ivec3 size, VkImageLayout current);
  void destroy(image& i);

  // `src` as a shader module, compiled once per distinct text and stage; failures carry mapped positions.
  result<const shader*> get_shader(const glsl::source& src, spirv::stage st, const std::string& label);

  // A pipeline that draws `fragment` into images of `color_formats` (dynamic rendering), with no vertex
  // input; fails before building when the fragment shader's outputs do not match the formats one to one
  // (locations 0..n-1, one output per target, as many components as the format has channels).
  result<pipeline> make_graphics_pipeline(const shader& vertex, const shader& fragment,
                                          const std::vector<format>& color_formats, const std::string& label,
                                          const pipeline_state& state = {});
  result<pipeline> make_compute_pipeline(const shader& compute, const std::string& label);
  void destroy(pipeline& p);

  // Records commands with `record`, submits them, waits, and returns the GPU time they took in ms.
  double submit(const std::function<void(VkCommandBuffer)>& record);

  // Many timed passes in one submission, as a renderer runs a frame: begin_passes opens dstrans's command
  // buffer for at most `max_passes` passes, record_pass records `record` between two timestamps (other
  // commands may go into the returned buffer between passes, untimed), and submit_passes submits it all
  // once, waits, and returns each pass's GPU time in ms in the order recorded, then the whole
  // submission's (from its first command to its last); a failure if more passes were recorded than asked.
  VkCommandBuffer begin_passes(std::size_t max_passes);
  void record_pass(const std::function<void(VkCommandBuffer)>& record);
  result<std::vector<double>> submit_passes();

  // Starts dynamic rendering into all of `t`, with a viewport of negative height so that clip-space +y
  // is the image's top row, as with GL's glClipControl(GL_UPPER_LEFT): one projection matrix serves both
  // APIs. `clear` holds one colour per target (and clears depth to 1); empty loads what is there. The
  // images are in GENERAL, or with `optimal` in COLOR_ATTACHMENT_OPTIMAL and DEPTH_STENCIL_ATTACHMENT_OPTIMAL.
  void begin_rendering(VkCommandBuffer cmd, const targets& t, const std::vector<glm::vec4>& clear, bool optimal = false);
  // Narrows the rendering begun to `area` (x, y from the top left, width, height): viewport and scissor.
  static void set_area(VkCommandBuffer cmd, glm::ivec4 area);
  void end_rendering(VkCommandBuffer cmd);
  // Sets the cull mode of a pipeline made with pipeline_state::dynamic_cull (vkCmdSetCullMode: Vulkan 1.3,
  // or VK_EXT_extended_dynamic_state where the engine enabled it); false, doing nothing, where the device
  // has neither, and its pipelines keep pipeline_state::cull.
  bool set_cull_mode(VkCommandBuffer cmd, VkCullModeFlags mode) const;

  // How many memory blocks (vkAllocateMemory calls) the device holds now.
  std::size_t memory_blocks() const;

  // Names a Vulkan object for frame captures and validation messages (VK_EXT_debug_utils, when enabled).
  void name(VkObjectType type, std::uint64_t handle, const std::string& text);

  // The packed results of `calls` calls of `f`, whose packed arguments follow each other in `args`.
  // Batches past the device's dispatch and storage-buffer limits run in several dispatches.
  result<words> run_formula(const formula& f, const words& args, std::size_t calls);

 private:
  result<words> run_dispatch(const pipeline& p, const formula& f, const words& args, std::size_t calls);
  explicit device(const context& ctx) : ctx_(ctx) {}
  result<std::uint32_t> memory_type(std::uint32_t bits, VkMemoryPropertyFlags flags) const;
  // A slice for `req` in a block of memory with `flags` (mapped if host-visible); `linear`: for a buffer.
  result<allocation> take(const VkMemoryRequirements& req, VkMemoryPropertyFlags flags, bool linear);
  void release(allocation& a);
  struct memory_block {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    std::uint32_t type = 0;
    bool linear = false;
    VkDeviceSize size = 0;
    void* mapped = nullptr;
    std::map<VkDeviceSize, VkDeviceSize> free;  // offset to size, coalesced
  };
  result<std::vector<std::uint8_t>> read_image(VkImage img, std::size_t bytes_per_pixel, int width, int height, VkImageLayout current,
                                               int depth = 1);
  result<image> make_image(VkFormat fmt, VkImageUsageFlags usage, VkImageAspectFlags aspect, int w, int h,
                           const std::string& label, VkImageViewType view_type = VK_IMAGE_VIEW_TYPE_2D,
                           int depth_or_layers = 1, int levels = 1);
  // A pipeline with its layouts made from what `stages` declare, and no VkPipeline yet.
  result<pipeline> pipeline_layout(const std::vector<const shader*>& stages, const std::string& label);

  context ctx_;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkQueryPool timestamps_ = VK_NULL_HANDLE;
  std::uint32_t timestamp_capacity_ = 0;
  std::size_t passes_ = 0, max_passes_ = 0;
  double timestamp_ns_ = 1.0;
  PFN_vkSetDebugUtilsObjectNameEXT set_name_ = nullptr;
  PFN_vkCmdBeginRendering begin_rendering_ = nullptr;
  PFN_vkCmdSetCullMode set_cull_mode_ = nullptr;
  PFN_vkCmdEndRendering end_rendering_ = nullptr;
  std::map<std::uint64_t, std::unique_ptr<shader>> shaders_;
  std::map<std::string, pipeline> formula_pipelines_;
  std::map<std::uint32_t, memory_block> blocks_;  // by id, from 1
  std::uint32_t next_block_ = 1;
};

}  // namespace dstrans::vk

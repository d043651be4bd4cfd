// A small Vulkan engine with its own device, queue, memory allocator, descriptor sets and deferred renderer,
// taking dstrans in one step at a time, as examples/engine_gl does on OpenGL (README.md):
//   --step 0  the engine as it was: its own G-buffer; glass is skipped
//   --step 1  dstrans's G-buffer layout (Table 3.1) and interlaced transparency
//   --step 2  + coloured shadows from the glass (Table 3.3 shadow map, Eq. 3.1)
//   --step 3  + refraction with depth rejection (Eq. 3.3)
//   --step 4  the whole frame through dstrans's renderer (dstrans_vk_frame.hpp), with hair, smoke and a
//             post chain, recorded into the engine's command buffer, the engine drawing its own buffers
// Up to step 3 dstrans brings GLSL text and, as the engine's shader compiler, dstrans_spirv (glslang); the
// engine's Vulkan objects are its own. --validate turns the Khronos validation layer on; any message fails the run.
//
//   engine_vk --step 3 --out step3.png --validate
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <dstrans/dstrans.hpp>
#include <dstrans_spirv.hpp>
#include <dstrans_vk_frame.hpp>  // [step 4] the whole frame

#include "../engine_world.hpp"
#include "../example_io.hpp"

#define STB_IMAGE_WRITE_IMPLEMENTATION  // stb_image_write.h's definitions, here once
#include <stb/stb_image_write.h>

namespace engine {

[[noreturn]] void fail(const char* what, VkResult r) {
  std::fprintf(stderr, "engine_vk: %s failed (%d)\n", what, int(r));
  std::exit(1);
}
#define CHECK_VK(call)                 \
  do {                                 \
    const VkResult r_ = (call);        \
    if (r_ != VK_SUCCESS) fail(#call, r_); \
  } while (0)

int validation_messages = 0;
VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  std::fprintf(stderr, "engine_vk: validation: %s\n", data->pMessage);
  ++validation_messages;
  return VK_FALSE;
}

// ---- The engine's device, queue and memory --------------------------------------------------------------

struct gpu {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t family = 0;
  VkCommandPool pool = VK_NULL_HANDLE;
};

gpu open_gpu(bool validate) {
  gpu g;
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "engine_vk";
  app.apiVersion = VK_API_VERSION_1_3;
  const char* layers[] = {"VK_LAYER_KHRONOS_validation"};
  const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
  VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ici.pApplicationInfo = &app;
  ici.enabledLayerCount = validate ? 1 : 0;
  ici.ppEnabledLayerNames = layers;
  ici.enabledExtensionCount = validate ? 1 : 0;
  ici.ppEnabledExtensionNames = extensions;
  CHECK_VK(vkCreateInstance(&ici, nullptr, &g.instance));
  if (validate) {
    VkDebugUtilsMessengerCreateInfoEXT m{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    m.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    m.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
    m.pfnUserCallback = on_message;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(g.instance, "vkCreateDebugUtilsMessengerEXT"));
    CHECK_VK(create(g.instance, &m, nullptr, &g.messenger));
  }
  uint32_t n = 0;
  vkEnumeratePhysicalDevices(g.instance, &n, nullptr);
  std::vector<VkPhysicalDevice> devices(n);
  vkEnumeratePhysicalDevices(g.instance, &n, devices.data());
  if (devices.empty()) fail("finding a Vulkan device", VK_ERROR_INITIALIZATION_FAILED);
  g.physical = devices[0];
  uint32_t families = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(g.physical, &families, nullptr);
  std::vector<VkQueueFamilyProperties> props(families);
  vkGetPhysicalDeviceQueueFamilyProperties(g.physical, &families, props.data());
  while (g.family < families && !(props[g.family].queueFlags & VK_QUEUE_GRAPHICS_BIT)) ++g.family;
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo q{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  q.queueFamilyIndex = g.family;
  q.queueCount = 1;
  q.pQueuePriorities = &priority;
  VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  v13.dynamicRendering = VK_TRUE;
  v13.synchronization2 = VK_TRUE;
  VkPhysicalDeviceFeatures features{};
  features.depthClamp = VK_TRUE;               // [step 4] dstrans draws light volumes depth-clamped
  features.fragmentStoresAndAtomics = VK_TRUE;  // [step 4] and fills the k-buffer from fragments
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.pNext = &v13;
  dci.pEnabledFeatures = &features;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &q;
  CHECK_VK(vkCreateDevice(g.physical, &dci, nullptr, &g.device));
  vkGetDeviceQueue(g.device, g.family, 0, &g.queue);
  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.queueFamilyIndex = g.family;
  CHECK_VK(vkCreateCommandPool(g.device, &pci, nullptr, &g.pool));
  return g;
}

// The engine's allocator: blocks of 64 MiB per memory type, handed out in aligned slices; host-visible
// blocks stay mapped.
struct allocator {
  const gpu* g = nullptr;
  struct block {
    uint32_t type;
    VkDeviceMemory memory;
    VkDeviceSize used, size;
    char* mapped;
  };
  struct slice {
    VkDeviceMemory memory;
    VkDeviceSize offset;
    void* mapped;  // null unless host visible
  };
  std::vector<block> blocks;

  slice take(VkMemoryRequirements req, VkMemoryPropertyFlags want) {
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(g->physical, &mp);
    uint32_t type = 0;
    while (type < mp.memoryTypeCount &&
           !((req.memoryTypeBits >> type & 1u) && (mp.memoryTypes[type].propertyFlags & want) == want))
      ++type;
    for (block& b : blocks) {
      const VkDeviceSize at = (b.used + req.alignment - 1) / req.alignment * req.alignment;
      if (b.type == type && at + req.size <= b.size) {
        b.used = at + req.size;
        return {b.memory, at, b.mapped ? b.mapped + at : nullptr};
      }
    }
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = std::max<VkDeviceSize>(req.size, 64u << 20);
    ai.memoryTypeIndex = type;
    VkDeviceMemory m;
    CHECK_VK(vkAllocateMemory(g->device, &ai, nullptr, &m));
    void* mapped = nullptr;
    if (want & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) CHECK_VK(vkMapMemory(g->device, m, 0, VK_WHOLE_SIZE, 0, &mapped));
    blocks.push_back({type, m, req.size, ai.allocationSize, static_cast<char*>(mapped)});
    return {m, 0, mapped};
  }
};

struct image {
  VkImage handle = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
};
struct buffer {
  VkBuffer handle = VK_NULL_HANDLE;
  void* mapped = nullptr;
};

// Render targets stay in VK_IMAGE_LAYOUT_GENERAL: drawn into by one pass, sampled by the next.
image make_image(const gpu& g, allocator& a, VkFormat f, int w, int h, bool depth) {
  image im;
  im.format = f;
  VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ici.imageType = VK_IMAGE_TYPE_2D;
  ici.format = f;
  ici.extent = {uint32_t(w), uint32_t(h), 1};
  ici.mipLevels = ici.arrayLayers = 1;
  ici.samples = VK_SAMPLE_COUNT_1_BIT;
  ici.usage = (depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT) |
              VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  CHECK_VK(vkCreateImage(g.device, &ici, nullptr, &im.handle));
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(g.device, im.handle, &req);
  const allocator::slice s = a.take(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  CHECK_VK(vkBindImageMemory(g.device, im.handle, s.memory, s.offset));
  VkImageViewCreateInfo v{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  v.image = im.handle;
  v.viewType = VK_IMAGE_VIEW_TYPE_2D;
  v.format = f;
  v.subresourceRange = {VkImageAspectFlags(depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT), 0, 1, 0, 1};
  CHECK_VK(vkCreateImageView(g.device, &v, nullptr, &im.view));
  return im;
}

buffer make_buffer(const gpu& g, allocator& a, VkDeviceSize size, VkBufferUsageFlags usage) {
  buffer b;
  VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bci.size = size;
  bci.usage = usage;
  CHECK_VK(vkCreateBuffer(g.device, &bci, nullptr, &b.handle));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(g.device, b.handle, &req);
  const allocator::slice s = a.take(req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  CHECK_VK(vkBindBufferMemory(g.device, b.handle, s.memory, s.offset));
  b.mapped = s.mapped;
  return b;
}

// ---- The engine's world ------------------------------------------------------------------------------------

struct vertex {
  glm::vec3 position, normal;
};
struct mesh {
  buffer vertices, indices;
  uint32_t count = 0;
};
struct material {
  glm::vec3 colour;
  float alpha = 1.0f;
  float specular = 0.2f, shininess = 16.0f;
};
struct object {
  mesh shape;
  glm::mat4 model;
  material look;
};

mesh upload(const gpu& g, allocator& a, const std::vector<vertex>& v, const std::vector<uint32_t>& idx) {
  mesh m;
  m.vertices = make_buffer(g, a, v.size() * sizeof(vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  m.indices = make_buffer(g, a, idx.size() * sizeof(uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  std::memcpy(m.vertices.mapped, v.data(), v.size() * sizeof(vertex));
  std::memcpy(m.indices.mapped, idx.data(), idx.size() * sizeof(uint32_t));
  m.count = uint32_t(idx.size());
  return m;
}
mesh box(const gpu& g, allocator& a, glm::vec3 size) {
  std::vector<vertex> v;
  std::vector<uint32_t> idx;
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {-1.0f, 1.0f}) {
      glm::vec3 n(0.0f), u(0.0f), w(0.0f);
      n[axis] = sign;
      u[(axis + 1) % 3] = 1.0f;
      w[(axis + 2) % 3] = 1.0f;
      if (sign < 0) std::swap(u, w);
      const uint32_t base = uint32_t(v.size());
      for (glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
        v.push_back({(n + u * c.x + w * c.y) * size * 0.5f, n});
      idx.insert(idx.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
  return upload(g, a, v, idx);
}
mesh quad(const gpu& g, allocator& a, glm::vec2 size) {
  const glm::vec3 n(0, 0, 1);
  const glm::vec2 h = size * 0.5f;
  return upload(g, a, {{{-h.x, -h.y, 0}, n}, {{h.x, -h.y, 0}, n}, {{h.x, h.y, 0}, n}, {{-h.x, h.y, 0}, n}},
                {0, 1, 2, 0, 2, 3});
}

// ---- The engine's shaders ----------------------------------------------------------------------------------

// One descriptor set for every pass: the frame's uniforms, then every image a pass may sample.
const char* const bindings = R"(
layout(set = 0, binding = 0) uniform engine_frame {
  mat4 view_proj, inv_view_proj, view, light_view_proj;
  vec4 light_position, light_direction_cos, light_colour, eye, ambient_refraction;
} frame;
layout(set = 0, binding = 1) uniform sampler2D engine_gbuffer[4];
layout(set = 0, binding = 2) uniform sampler2D engine_light;
layout(set = 0, binding = 3) uniform sampler2D engine_shadow_map[2];
layout(push_constant) uniform engine_object {
  mat4 model;
  vec4 colour_alpha;
  vec4 specular_shininess_size;   // specular, shininess, the target's width and height
} object;
)";
const char* const geometry_vs = R"(
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 0) out vec3 world_normal;
void main() {
  world_normal = mat3(object.model) * normal;
  gl_Position = frame.view_proj * object.model * vec4(position, 1.0);
}
)";
// The shadow pass draws the same geometry seen from the light.
const char* const shadow_vs = R"(
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 0) out vec3 world_normal;
void main() {
  world_normal = mat3(object.model) * normal;
  gl_Position = frame.light_view_proj * object.model * vec4(position, 1.0);
}
)";
// Step 0: the engine's own G-buffer: albedo + specular, normal + shininess, depth.
const char* const own_gbuffer_fs = R"(
layout(location = 0) in vec3 world_normal;
layout(location = 0) out vec4 albedo_specular;
layout(location = 1) out vec4 normal_shininess;
layout(location = 2) out float depth;
void main() {
  albedo_specular = vec4(object.colour_alpha.rgb, object.specular_shininess_size.x);
  normal_shininess = vec4(normalize(world_normal), object.specular_shininess_size.y);
  depth = gl_FragCoord.z;
}
)";
// [step 1] Through dstrans: Table 3.1 by dst_gbuffer_write, glass only on the rows the predicate keeps.
const char* const dstrans_gbuffer_fs = R"(
layout(location = 0) in vec3 world_normal;
void main() {
  if (object.colour_alpha.a < 1.0 &&
      !dst_interlace_keep(ivec2(gl_FragCoord.xy), ivec2(object.specular_shininess_size.zw))) discard;
  dst_surface s = dst_surface_zero();
  s.diffuse = object.colour_alpha.rgb;
  s.alpha = object.colour_alpha.a;
  vec3 n = normalize(world_normal);
  s.normal = gl_FrontFacing ? n : -n;
  s.spec_intensity = object.specular_shininess_size.x;
  s.spec_power = object.specular_shininess_size.y;
  s.depth = gl_FragCoord.z;
  dst_gbuffer_write(s);
}
)";
const char* const fullscreen_vs = R"(
void main() { gl_Position = vec4(vec2(gl_VertexIndex & 1, gl_VertexIndex >> 1) * 4.0 - 1.0, 0.0, 1.0); }
)";
// The light pass: one spot light; rows from the top (the engine draws with a negative viewport height).
const char* const light_fs = R"(
layout(location = 0) out vec4 light_out;
void engine_surface(ivec2 p, out vec3 n, out float shininess, out float depth);
vec3 engine_shadow(vec3 world, vec3 light);
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy), size = textureSize(engine_light_size_source, 0);
  vec3 n;
  float shininess, depth;
  engine_surface(p, n, shininess, depth);
  if (depth >= 1.0) discard;
  vec2 ndc = vec2((float(p.x) + 0.5) / float(size.x) * 2.0 - 1.0, 1.0 - (float(p.y) + 0.5) / float(size.y) * 2.0);
  vec4 h = frame.inv_view_proj * vec4(ndc, depth, 1.0);
  vec3 world = h.xyz / h.w;
  vec3 to_light = normalize(frame.light_position.xyz - world);
  float cone = smoothstep(frame.light_direction_cos.w, frame.light_direction_cos.w + 0.05,
                          dot(-to_light, frame.light_direction_cos.xyz));
  vec3 light = engine_shadow(world, frame.light_colour.rgb * cone);
  float ndotl = max(dot(n, to_light), 0.0);
  vec3 r = reflect(-to_light, n);
  float spec = ndotl > 0.0 ? pow(max(dot(r, normalize(frame.eye.xyz - world)), 0.0), shininess) : 0.0;
  light_out = vec4(light * ndotl, spec * (light.x + light.y + light.z) / 3.0);
}
)";
const char* const own_surface = R"(
#define engine_light_size_source engine_gbuffer[0]
void engine_surface(ivec2 p, out vec3 n, out float shininess, out float depth) {
  vec4 t = texelFetch(engine_gbuffer[1], p, 0);
  n = t.xyz;
  shininess = t.w;
  depth = texelFetch(engine_gbuffer[2], p, 0).x;
}
)";
// [step 1] The light pass reads the surface through dstrans's layout.
const char* const dstrans_surface = R"(
#define engine_light_size_source engine_gbuffer[0]
void engine_surface(ivec2 p, out vec3 n, out float shininess, out float depth) {
  dst_surface s = dst_gbuffer_read(p);
  n = s.normal;
  shininess = s.spec_power;
  depth = s.depth;
}
)";
const char* const no_shadow = "vec3 engine_shadow(vec3 world, vec3 light) { return light; }\n";
// [step 2] Coloured shadows: the texel and its interlace partner in Table 3.3's map, Eq. 3.1.
const char* const dstrans_shadow = R"(
vec3 engine_shadow(vec3 world, vec3 light) {
  vec4 h = frame.light_view_proj * vec4(world, 1.0);
  vec3 c = h.xyz / h.w;
  ivec2 size = textureSize(engine_shadow_map[0], 0);
  ivec2 t = ivec2(vec2(c.x * 0.5 + 0.5, 0.5 - c.y * 0.5) * vec2(size));
  if (h.w <= 0.0 || any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, size))) return light;
  ivec2 o = dst_interlace_partner(t, size);
  dst_surface a = dst_shadow_read(t), b = dst_shadow_read(o);
  return dst_transparent_shadow(light, c.z, 0.002, a.depth, vec4(a.diffuse, a.alpha), b.depth, vec4(b.diffuse, b.alpha));
}
)";
const char* const own_compose_fs = R"(
layout(location = 0) out vec4 colour_out;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 a = texelFetch(engine_gbuffer[0], p, 0), l = texelFetch(engine_light, p, 0);
  colour_out = vec4(a.rgb * (l.rgb + frame.ambient_refraction.rgb) + a.w * l.w, 1.0);
}
)";
// [step 1] De-interlacing and Eq. 3.3 with dst_compose; [step 3] refraction.
const char* const dstrans_compose_fs = R"(
layout(location = 0) out vec4 colour_out;
dst_light_sample engine_light_at(ivec2 p) {
  vec4 l = texelFetch(engine_light, p, 0);
  dst_light_sample s;
  s.light = l.rgb;
  s.specular = vec3(l.w);
  return s;
}
void main() {
  vec3 ambient = frame.ambient_refraction.rgb;
  ivec2 p = ivec2(gl_FragCoord.xy), size = textureSize(engine_light, 0);
  ivec2 q = dst_interlace_partner(p, size);
  dst_surface a = dst_gbuffer_read(p), b = dst_gbuffer_read(q);
  if (a.alpha >= 1.0 && b.alpha >= 1.0) {
    colour_out = vec4(dst_shade(a, engine_light_at(p), ambient), 1.0);
    return;
  }
  bool a_glass = a.alpha <= b.alpha;
  dst_surface t = a_glass ? a : b, o = a_glass ? b : a;
  dst_light_sample lt = engine_light_at(a_glass ? p : q), lo = engine_light_at(a_glass ? q : p);
  if (frame.ambient_refraction.w > 0.0) {
    ivec2 m = dst_refraction_pixel(p, size, mat3(frame.view) * t.normal, frame.ambient_refraction.w);
    ivec2 m2 = dst_interlace_partner(m, size);
    dst_surface r = dst_gbuffer_read(m), r2 = dst_gbuffer_read(m2);
    int from = dst_refraction_source(t.depth, r.alpha, r.depth, r2.alpha, r2.depth);
    if (from != 0) {
      o = from == 1 ? r : r2;
      lo = engine_light_at(from == 1 ? m : m2);
    }
  }
  colour_out = vec4(dst_compose(o, lo, t, lt, ambient), 1.0);
}
)";

// [step 1] A shader of the engine with dstrans's text in front: the layouts fetch through the engine's
// own descriptor set (the hooks), with the interlace predicate and the shared formulas the passes call.
dstrans::glsl::source shader(const std::string& engine_text, bool gbuffer_write, bool shadow_write) {
  dstrans::glsl::source src;
  src.add(bindings, __FILE__, __LINE__);
  src.add("#define DSTRANS_GBUFFER_FETCH\n"
          "vec4 dst_gbuffer_fetch(int t, ivec2 p) { return texelFetch(engine_gbuffer[t], p, 0); }\n"
          "#define DSTRANS_SHADOW_FETCH\n"
          "vec4 dst_shadow_fetch(int t, ivec2 p) { return texelFetch(engine_shadow_map[t], p, 0); }\n",
          __FILE__, __LINE__);
  dstrans::glsl::layout_options o;
  o.sides = gbuffer_write ? dstrans::glsl::side::write : dstrans::glsl::side::read;
  dstrans::glsl::add_layout<dstrans::thesis_gbuffer>(src, "gbuffer", o);
  o.sides = shadow_write ? dstrans::glsl::side::write : dstrans::glsl::side::read;
  dstrans::glsl::add_layout<dstrans::thesis_shadow_map>(src, "shadow", o);
  dstrans::glsl::add_interlace<dstrans::interlace::rows>(src);
  for (const dstrans::shared_text* t : {&dstrans::text::dst_compose, &dstrans::text::dst_refraction,
                                        &dstrans::text::dst_transparent_shadow})
    src.add_shared(*t);
  src.add(engine_text, __FILE__, __LINE__);
  return src;
}
// Step 0: the engine's own text only.
dstrans::glsl::source own_shader(const std::string& engine_text) {
  dstrans::glsl::source src;
  src.add(bindings, __FILE__, __LINE__);
  src.add(engine_text, __FILE__, __LINE__);
  return src;
}

VkShaderModule module(const gpu& g, const dstrans::glsl::source& src, dstrans::spirv::stage st) {
  const auto words = dstrans::spirv::compile(src, st, dstrans::spirv::api::vulkan);
  if (!words) {
    std::fprintf(stderr, "engine_vk: %s\n", words.error().c_str());
    std::exit(1);
  }
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = words->size() * 4;
  ci.pCode = words->data();
  VkShaderModule m;
  CHECK_VK(vkCreateShaderModule(g.device, &ci, nullptr, &m));
  return m;
}

// A pipeline for dynamic rendering into `colours` (and depth when `depth_test`).
VkPipeline pipeline(const gpu& g, VkPipelineLayout layout, VkShaderModule vs, VkShaderModule fs,
                    const std::vector<VkFormat>& colours, bool depth_test, bool scene_vertices, bool additive) {
  VkPipelineShaderStageCreateInfo stages[2]{{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                           {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vs;
  stages[0].pName = "main";
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fs;
  stages[1].pName = "main";
  const VkVertexInputBindingDescription vb{0, sizeof(vertex), VK_VERTEX_INPUT_RATE_VERTEX};
  const VkVertexInputAttributeDescription va[2]{{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},
                                                {1, 0, VK_FORMAT_R32G32B32_SFLOAT, sizeof(glm::vec3)}};
  VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  if (scene_vertices) {
    vi.vertexBindingDescriptionCount = 1;
    vi.pVertexBindingDescriptions = &vb;
    vi.vertexAttributeDescriptionCount = 2;
    vi.pVertexAttributeDescriptions = va;
  }
  VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = vp.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  rs.cullMode = VK_CULL_MODE_NONE;
  rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  rs.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = ds.depthWriteEnable = depth_test;
  ds.depthCompareOp = VK_COMPARE_OP_LESS;
  std::vector<VkPipelineColorBlendAttachmentState> blend(colours.size());
  for (auto& b : blend) {
    b.colorWriteMask = 0xf;
    b.blendEnable = additive;
    b.srcColorBlendFactor = b.dstColorBlendFactor = b.srcAlphaBlendFactor = b.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
  }
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = uint32_t(blend.size());
  cb.pAttachments = blend.data();
  const VkDynamicState dyn[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dy.dynamicStateCount = 2;
  dy.pDynamicStates = dyn;
  VkPipelineRenderingCreateInfo ri{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  ri.colorAttachmentCount = uint32_t(colours.size());
  ri.pColorAttachmentFormats = colours.data();
  ri.depthAttachmentFormat = depth_test ? VK_FORMAT_D32_SFLOAT : VK_FORMAT_UNDEFINED;
  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  ci.pNext = &ri;
  ci.stageCount = 2;
  ci.pStages = stages;
  ci.pVertexInputState = &vi;
  ci.pInputAssemblyState = &ia;
  ci.pViewportState = &vp;
  ci.pRasterizationState = &rs;
  ci.pMultisampleState = &ms;
  ci.pDepthStencilState = &ds;
  ci.pColorBlendState = &cb;
  ci.pDynamicState = &dy;
  ci.layout = layout;
  VkPipeline p;
  CHECK_VK(vkCreateGraphicsPipelines(g.device, VK_NULL_HANDLE, 1, &ci, nullptr, &p));
  return p;
}

// [step 1] The Vulkan format of a dstrans target: the engine allocates dstrans's layouts itself.
VkFormat vk_format(dstrans::format f) {
  switch (f) {
    case dstrans::format::rgba8: return VK_FORMAT_R8G8B8A8_UNORM;
    case dstrans::format::rgb10a2: return VK_FORMAT_A2B10G10R10_UNORM_PACK32;
    case dstrans::format::r32f: return VK_FORMAT_R32_SFLOAT;
    default: return VK_FORMAT_R32G32B32A32_SFLOAT;
  }
}
template <class Layout>
std::vector<VkFormat> formats_of() {
  std::vector<VkFormat> out;
  for (const dstrans::target_desc& d : dstrans::describe<Layout>()) out.push_back(vk_format(d.fmt));
  return out;
}

struct frame_uniforms {
  glm::mat4 view_proj, inv_view_proj, view, light_view_proj;
  glm::vec4 light_position, light_direction_cos, light_colour, eye, ambient_refraction;
};
struct object_constants {
  glm::mat4 model;
  glm::vec4 colour_alpha, specular_shininess_size;
};

}  // namespace engine

namespace engine {

// Ends `cmd`, submits it to the engine's queue and waits until it is done.
void submit_and_wait(const gpu& g, VkCommandBuffer cmd) {
  CHECK_VK(vkEndCommandBuffer(cmd));
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  CHECK_VK(vkQueueSubmit(g.queue, 1, &si, VK_NULL_HANDLE));
  CHECK_VK(vkQueueWaitIdle(g.queue));
}

// Frees the engine's memory and closes its device and instance.
void close_gpu(gpu& g, allocator& mem) {
  for (const allocator::block& b : mem.blocks) vkFreeMemory(g.device, b.memory, nullptr);
  vkDestroyCommandPool(g.device, g.pool, nullptr);
  vkDestroyDevice(g.device, nullptr);
  if (g.messenger) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(g.instance, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(g.instance, g.messenger, nullptr);
  }
  vkDestroyInstance(g.instance, nullptr);
}

// [step 4] The whole frame: dstrans's renderer, made on the engine's instance, device and queue, records
// every pass into the engine's command buffer, which the engine submits. The engine hands it a description
// of the world and its vertex layout (position and normal interleaved at binding 0, the material an
// instance-rate stream at binding 1), and draws its own buffers when a geometry pass asks.
bool whole_frame(const gpu& g, allocator& mem, const std::string& out, int w, int h) {
  const dstrans::scene world = example::engine_world();
  const dstrans::vk::context ctx{g.instance, g.physical, g.device, g.queue, g.family, nullptr, g.messenger != VK_NULL_HANDLE};
  auto dev = dstrans::vk::device::create(ctx);
  if (!dev) {
    std::fprintf(stderr, "engine_vk: %s\n", dev.error().c_str());
    return false;
  }
  struct drawn_mesh {
    mesh shape;
    uint32_t material;
    bool hair;
  };
  std::vector<drawn_mesh> meshes;
  for (const dstrans::object& o : world.objects) {
    std::vector<vertex> v;
    for (const example::world_vertex& p : example::world_vertices(world, o)) v.push_back({p.position, p.normal});
    meshes.push_back({upload(g, mem, v, o.geometry.indices), o.material, world.materials[o.material].hair});
  }
  std::vector<uint32_t> material_ids(world.materials.size());
  for (uint32_t k = 0; k < material_ids.size(); ++k) material_ids[k] = k;
  const buffer materials = make_buffer(g, mem, material_ids.size() * sizeof(uint32_t), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  std::memcpy(materials.mapped, material_ids.data(), material_ids.size() * sizeof(uint32_t));
  dstrans::vk::vertex_input layout;
  layout.bindings = {{0, sizeof(vertex), VK_VERTEX_INPUT_RATE_VERTEX}, {1, sizeof(uint32_t), VK_VERTEX_INPUT_RATE_INSTANCE}};
  layout.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, uint32_t(offsetof(vertex, position))},
                       {1, 0, VK_FORMAT_R32G32B32_SFLOAT, uint32_t(offsetof(vertex, normal))},
                       {2, 1, VK_FORMAT_R32_UINT, 0}};
  dstrans::render::options o;  // as dstrans render draws a scene
  o.width = w;
  o.height = h;
  o.shadow_size = 1024;
  o.opaque_shadows_depth_only = true;  // the callback tells opaque materials from the rest (dstrans::draws)
  auto r = dstrans::vk::renderer::create(**dev, world, o, dstrans::pass_shaders(), layout);
  bool written = false;
  if (!r) {
    std::fprintf(stderr, "engine_vk: %s\n", r.error().c_str());
  } else {
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = g.pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    CHECK_VK(vkAllocateCommandBuffers(g.device, &ai, &cmd));
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    CHECK_VK(vkBeginCommandBuffer(cmd, &bi));
    (*r)->record(cmd, world.view, [&](VkCommandBuffer c, const dstrans::scheduled_pass& pass) {
      for (const bool hair : {false, true})  // surfaces first, as dstrans orders them
        for (const drawn_mesh& m : meshes) {
          if (m.hair != hair || !dstrans::draws(pass.draws, world.materials[m.material])) continue;
          const VkBuffer streams[] = {m.shape.vertices.handle, materials.handle};
          const VkDeviceSize offsets[] = {0, VkDeviceSize(m.material) * sizeof(uint32_t)};  // instance 0 reads its material
          vkCmdBindVertexBuffers(c, 0, 2, streams, offsets);
          vkCmdBindIndexBuffer(c, m.shape.indices.handle, 0, VK_INDEX_TYPE_UINT32);
          vkCmdDrawIndexed(c, m.shape.count, 1, 0, 0, 0);
        }
    });
    submit_and_wait(g, cmd);
    auto texels = (*dev)->read_texels((*r)->output(), 0, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    std::vector<unsigned char> pixels;  // RGBA8, rows from the top
    if (texels)
      for (const dstrans::texel& t : *texels) pixels.insert(pixels.end(), t.begin(), t.begin() + 4);
    std::string error;
    written = texels && example::write_png(out, w, h, pixels.data(), false, error);
    if (!written) std::fprintf(stderr, "engine_vk: %s\n", texels ? error.c_str() : texels.error().c_str());
    vkFreeCommandBuffers(g.device, g.pool, 1, &cmd);
  }
  for (const drawn_mesh& m : meshes) {
    vkDestroyBuffer(g.device, m.shape.vertices.handle, nullptr);
    vkDestroyBuffer(g.device, m.shape.indices.handle, nullptr);
  }
  vkDestroyBuffer(g.device, materials.handle, nullptr);
  return written;
}

}  // namespace engine

int main(int argc, char** argv) {
  int step = 3;
  bool validate = false;
  std::string out = "engine_vk.png";
  const char* const usage = "usage: engine_vk [--step 0|1|2|3|4] [--out image.png] [--validate]\n";
  if (const int stop = example::engine_arguments(argc, argv, "engine_vk", usage, step, out, &validate); stop >= 0) return stop;
  using namespace engine;
  const int w = 320, h = 180, shadow_size = 512;
  gpu g = open_gpu(validate);
  allocator mem{&g, {}};
  if (step == 4) {
    const bool written = whole_frame(g, mem, out, w, h);
    close_gpu(g, mem);
    if (validation_messages) std::fprintf(stderr, "engine_vk: %d validation messages\n", validation_messages);
    if (!written || validation_messages) return 1;
    std::printf("engine_vk: step 4: %s\n", out.c_str());
    return 0;
  }
  const bool dstrans_gbuffer = step >= 1, shadows = step >= 2;

  // The world (the same as engine_gl's).
  const std::vector<object> world{
      {box(g, mem, {8.0f, 0.1f, 8.0f}), glm::translate(glm::mat4(1), {0, -0.05f, 0}), {{0.8f, 0.8f, 0.8f}}},
      {box(g, mem, {0.6f, 0.6f, 0.6f}), glm::translate(glm::mat4(1), {0.6f, 0.3f, -1.0f}), {{0.8f, 0.2f, 0.1f}, 1.0f, 0.5f, 32.0f}},
      {quad(g, mem, {1.4f, 1.0f}), glm::translate(glm::mat4(1), {-0.3f, 0.6f, 0.3f}), {{0.2f, 0.5f, 1.0f}, 0.4f, 0.9f, 64.0f}},
      {quad(g, mem, {0.8f, 0.8f}), glm::rotate(glm::translate(glm::mat4(1), {1.0f, 0.5f, 0.8f}), 0.5f, {0, 1, 0}),
       {{0.2f, 1.0f, 0.3f}, 0.5f, 0.9f, 64.0f}}};
  const glm::vec3 eye(0.0f, 1.6f, 3.6f), light_position(-1.0f, 3.5f, 2.5f);
  const glm::vec3 light_direction = glm::normalize(glm::vec3(0.4f, -1.0f, -0.9f));
  const float cos_cone = 0.8f;
  frame_uniforms fu;
  fu.view = glm::lookAt(eye, glm::vec3(0, 0.5f, 0), glm::vec3(0, 1, 0));
  fu.view_proj = glm::perspectiveRH_ZO(glm::radians(55.0f), float(w) / float(h), 0.1f, 30.0f) * fu.view;
  fu.inv_view_proj = glm::inverse(fu.view_proj);
  fu.light_view_proj = glm::perspectiveRH_ZO(glm::acos(cos_cone) * 2.0f, 1.0f, 0.1f, 20.0f) *
                       glm::lookAt(light_position, light_position + light_direction, glm::vec3(0, 1, 0));
  fu.light_position = glm::vec4(light_position, 1.0f);
  fu.light_direction_cos = glm::vec4(light_direction, cos_cone);
  fu.light_colour = glm::vec4(1.6f, 1.5f, 1.4f, 0.0f);
  fu.eye = glm::vec4(eye, 1.0f);
  fu.ambient_refraction = glm::vec4(glm::vec3(0.08f), step >= 3 ? 8.0f : 0.0f);  // [step 3] strength in pixels
  buffer ubo = make_buffer(g, mem, sizeof fu, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  std::memcpy(ubo.mapped, &fu, sizeof fu);

  // Targets: the G-buffer (the engine's, or from step 1 Table 3.1's), the light buffer, the final image,
  // the shadow map (Table 3.3), and a depth buffer for each of the two views.
  const std::vector<VkFormat> gbuffer_formats =
      dstrans_gbuffer ? formats_of<dstrans::thesis_gbuffer>()
                      : std::vector<VkFormat>{VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R32_SFLOAT};
  std::vector<image> gbuffer;
  for (VkFormat f : gbuffer_formats) gbuffer.push_back(make_image(g, mem, f, w, h, false));
  const image light = make_image(g, mem, VK_FORMAT_R16G16B16A16_SFLOAT, w, h, false);
  const image final_image = make_image(g, mem, VK_FORMAT_R8G8B8A8_UNORM, w, h, false);
  const image depth = make_image(g, mem, VK_FORMAT_D32_SFLOAT, w, h, true);
  std::vector<image> shadow_map;
  for (VkFormat f : formats_of<dstrans::thesis_shadow_map>()) shadow_map.push_back(make_image(g, mem, f, shadow_size, shadow_size, false));
  const image shadow_depth = make_image(g, mem, VK_FORMAT_D32_SFLOAT, shadow_size, shadow_size, true);

  // The descriptor set: its layout, pool and contents are the engine's.
  VkSampler sampler;
  VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  CHECK_VK(vkCreateSampler(g.device, &sci, nullptr, &sampler));
  const VkShaderStageFlags all = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  const VkDescriptorSetLayoutBinding lb[] = {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, all, nullptr},
                                             {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4, all, nullptr},
                                             {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, all, nullptr},
                                             {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2, all, nullptr}};
  VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  lci.bindingCount = 4;
  lci.pBindings = lb;
  VkDescriptorSetLayout set_layout;
  CHECK_VK(vkCreateDescriptorSetLayout(g.device, &lci, nullptr, &set_layout));
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1}, {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 7}};
  VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dpci.maxSets = 1;
  dpci.poolSizeCount = 2;
  dpci.pPoolSizes = sizes;
  VkDescriptorPool pool;
  CHECK_VK(vkCreateDescriptorPool(g.device, &dpci, nullptr, &pool));
  VkDescriptorSetAllocateInfo dsai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  dsai.descriptorPool = pool;
  dsai.descriptorSetCount = 1;
  dsai.pSetLayouts = &set_layout;
  VkDescriptorSet set;
  CHECK_VK(vkAllocateDescriptorSets(g.device, &dsai, &set));
  const VkDescriptorBufferInfo ubo_info{ubo.handle, 0, sizeof fu};
  std::vector<VkDescriptorImageInfo> gb_info(4), sm_info(2);
  for (std::size_t i = 0; i < 4; ++i) gb_info[i] = {sampler, gbuffer[std::min(i, gbuffer.size() - 1)].view, VK_IMAGE_LAYOUT_GENERAL};
  for (std::size_t i = 0; i < 2; ++i) sm_info[i] = {sampler, shadow_map[i].view, VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorImageInfo light_info{sampler, light.view, VK_IMAGE_LAYOUT_GENERAL};
  VkWriteDescriptorSet writes[4]{};
  for (auto& wr : writes) {
    wr.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    wr.dstSet = set;
    wr.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  }
  writes[0].dstBinding = 0;
  writes[0].descriptorCount = 1;
  writes[0].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  writes[0].pBufferInfo = &ubo_info;
  writes[1].dstBinding = 1;
  writes[1].descriptorCount = 4;
  writes[1].pImageInfo = gb_info.data();
  writes[2].dstBinding = 2;
  writes[2].descriptorCount = 1;
  writes[2].pImageInfo = &light_info;
  writes[3].dstBinding = 3;
  writes[3].descriptorCount = 2;
  writes[3].pImageInfo = sm_info.data();
  vkUpdateDescriptorSets(g.device, 4, writes, 0, nullptr);
  const VkPushConstantRange push{all, 0, sizeof(object_constants)};
  VkPipelineLayoutCreateInfo plci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  plci.setLayoutCount = 1;
  plci.pSetLayouts = &set_layout;
  plci.pushConstantRangeCount = 1;
  plci.pPushConstantRanges = &push;
  VkPipelineLayout layout;
  CHECK_VK(vkCreatePipelineLayout(g.device, &plci, nullptr, &layout));

  // The passes' pipelines.
  using dstrans::spirv::stage;
  std::vector<VkShaderModule> modules;  // freed once the pipelines exist
  auto compiled = [&](const dstrans::glsl::source& src, stage st) {
    modules.push_back(module(g, src, st));
    return modules.back();
  };
  auto with_dstrans = [&](const char* text, bool gbuffer_write, bool shadow_write) {
    return dstrans_gbuffer ? shader(text, gbuffer_write, shadow_write) : own_shader(text);
  };
  const VkShaderModule geometry_vs_m = compiled(own_shader(geometry_vs), stage::vertex),
                       shadow_vs_m = compiled(own_shader(shadow_vs), stage::vertex),
                       fullscreen_vs_m = compiled(own_shader(fullscreen_vs), stage::vertex);
  const VkPipeline geometry = pipeline(g, layout, geometry_vs_m,
                                       compiled(with_dstrans(dstrans_gbuffer ? dstrans_gbuffer_fs : own_gbuffer_fs, true, false), stage::fragment),
                                       gbuffer_formats, true, true, false);
  VkPipeline shadow = VK_NULL_HANDLE;
  if (shadows) {
    const std::string text = std::string("#define dst_gbuffer_write dst_shadow_write\n") + dstrans_gbuffer_fs;
    shadow = pipeline(g, layout, shadow_vs_m, compiled(shader(text, false, true), stage::fragment),
                      formats_of<dstrans::thesis_shadow_map>(), true, true, false);
  }
  const std::string light_text = std::string(dstrans_gbuffer ? dstrans_surface : own_surface) + light_fs +
                                 (shadows ? dstrans_shadow : no_shadow);
  const VkPipeline lighting = pipeline(g, layout, fullscreen_vs_m, compiled(with_dstrans(light_text.c_str(), false, false), stage::fragment),
                                       {light.format}, false, false, true);
  const VkPipeline compose =
      pipeline(g, layout, fullscreen_vs_m,
               compiled(with_dstrans(dstrans_gbuffer ? dstrans_compose_fs : own_compose_fs, false, false), stage::fragment),
               {final_image.format}, false, false, false);

  for (VkShaderModule m : modules) vkDestroyShaderModule(g.device, m, nullptr);

  // One command buffer: layouts to GENERAL, then the passes with a barrier between each.
  VkCommandBufferAllocateInfo cbai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  cbai.commandPool = g.pool;
  cbai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  cbai.commandBufferCount = 1;
  VkCommandBuffer cmd;
  CHECK_VK(vkAllocateCommandBuffers(g.device, &cbai, &cmd));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  CHECK_VK(vkBeginCommandBuffer(cmd, &begin));
  std::vector<VkImageMemoryBarrier2> to_general;
  auto general = [&](const image& im, bool is_depth) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = VK_PIPELINE_STAGE_2_NONE;
    b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    b.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
    b.image = im.handle;
    b.subresourceRange = {VkImageAspectFlags(is_depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT), 0, 1, 0, 1};
    to_general.push_back(b);
  };
  for (const image& im : gbuffer) general(im, false);
  for (const image& im : shadow_map) general(im, false);
  for (const image* im : {&light, &final_image}) general(*im, false);
  for (const image* im : {&depth, &shadow_depth}) general(*im, true);
  auto barrier = [&](const std::vector<VkImageMemoryBarrier2>& images) {
    VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    mb.srcStageMask = mb.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    mb.srcAccessMask = mb.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    di.memoryBarrierCount = 1;
    di.pMemoryBarriers = &mb;
    di.imageMemoryBarrierCount = uint32_t(images.size());
    di.pImageMemoryBarriers = images.data();
    vkCmdPipelineBarrier2(cmd, &di);
  };
  barrier(to_general);
  auto render = [&](const std::vector<image>& colours, const std::vector<glm::vec4>& clears, const image* depth_target,
                    int width, int height) {
    std::vector<VkRenderingAttachmentInfo> att(colours.size(), {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO});
    for (std::size_t i = 0; i < colours.size(); ++i) {
      att[i].imageView = colours[i].view;
      att[i].imageLayout = VK_IMAGE_LAYOUT_GENERAL;
      att[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
      att[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
      std::memcpy(att[i].clearValue.color.float32, &clears[std::min(i, clears.size() - 1)], sizeof(glm::vec4));
    }
    VkRenderingAttachmentInfo d{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    ri.renderArea = {{0, 0}, {uint32_t(width), uint32_t(height)}};
    ri.layerCount = 1;
    ri.colorAttachmentCount = uint32_t(att.size());
    ri.pColorAttachments = att.data();
    if (depth_target) {
      d.imageView = depth_target->view;
      d.imageLayout = VK_IMAGE_LAYOUT_GENERAL;
      d.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
      d.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
      d.clearValue.depthStencil = {1.0f, 0};
      ri.pDepthAttachment = &d;
    }
    vkCmdBeginRendering(cmd, &ri);
    // A negative height puts row 0 at the top with GL-style projections, as dstrans's passes expect.
    const VkViewport vp{0.0f, float(height), float(width), -float(height), 0.0f, 1.0f};
    const VkRect2D sc{{0, 0}, {uint32_t(width), uint32_t(height)}};
    vkCmdSetViewport(cmd, 0, 1, &vp);
    vkCmdSetScissor(cmd, 0, 1, &sc);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
  };
  auto draw_world = [&](VkPipeline p, bool with_glass, glm::ivec2 size) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p);
    for (const object& o : world) {
      if (o.look.alpha < 1.0f && !with_glass) continue;
      const object_constants c{o.model, glm::vec4(o.look.colour, o.look.alpha),
                               glm::vec4(o.look.specular, o.look.shininess, float(size.x), float(size.y))};
      vkCmdPushConstants(cmd, layout, all, 0, sizeof c, &c);
      const VkDeviceSize offset = 0;
      vkCmdBindVertexBuffers(cmd, 0, 1, &o.shape.vertices.handle, &offset);
      vkCmdBindIndexBuffer(cmd, o.shape.indices.handle, 0, VK_INDEX_TYPE_UINT32);
      vkCmdDrawIndexed(cmd, o.shape.count, 1, 0, 0, 0);
    }
  };
  const glm::vec4 black(0, 0, 0, 1), far(1.0f), zero(0.0f);
  // Geometry: the engine skipped glass until dstrans could keep it in the G-buffer.
  // The depth target (Table 3.1's RT3, or the engine's third) starts at the far plane.
  render(gbuffer, dstrans_gbuffer ? std::vector<glm::vec4>{black, black, black, far} : std::vector<glm::vec4>{black, black, far},
         &depth, w, h);
  draw_world(geometry, dstrans_gbuffer, {w, h});
  vkCmdEndRendering(cmd);
  barrier({});
  // [step 2] The shadow map, glass interlaced as in the G-buffer, seen from the light.
  if (shadows) {
    render(shadow_map, {far}, &shadow_depth, shadow_size, shadow_size);
    draw_world(shadow, true, {shadow_size, shadow_size});
    vkCmdEndRendering(cmd);
    barrier({});
  }
  render({light}, {zero}, nullptr, w, h);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, lighting);
  vkCmdDraw(cmd, 3, 1, 0, 0);
  vkCmdEndRendering(cmd);
  barrier({});
  render({final_image}, {zero}, nullptr, w, h);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, compose);
  vkCmdDraw(cmd, 3, 1, 0, 0);
  vkCmdEndRendering(cmd);
  barrier({});
  // Read the final image back.
  buffer readback = make_buffer(g, mem, VkDeviceSize(w) * h * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {uint32_t(w), uint32_t(h), 1};
  vkCmdCopyImageToBuffer(cmd, final_image.handle, VK_IMAGE_LAYOUT_GENERAL, readback.handle, 1, &copy);
  barrier({});
  submit_and_wait(g, cmd);
  std::string error;
  const bool written = example::write_png(out, w, h, readback.mapped, false, error);
  if (!written) std::fprintf(stderr, "engine_vk: %s\n", error.c_str());
  // Tear down: everything the engine made, in reverse (a failed write too).
  vkDeviceWaitIdle(g.device);
  for (VkPipeline p : {geometry, shadow, lighting, compose})
    if (p) vkDestroyPipeline(g.device, p, nullptr);
  vkDestroyPipelineLayout(g.device, layout, nullptr);
  vkDestroyDescriptorPool(g.device, pool, nullptr);
  vkDestroyDescriptorSetLayout(g.device, set_layout, nullptr);
  vkDestroySampler(g.device, sampler, nullptr);
  std::vector<image> images = gbuffer;
  images.insert(images.end(), shadow_map.begin(), shadow_map.end());
  images.insert(images.end(), {light, final_image, depth, shadow_depth});
  for (const image& im : images) {
    vkDestroyImageView(g.device, im.view, nullptr);
    vkDestroyImage(g.device, im.handle, nullptr);
  }
  std::vector<VkBuffer> buffers{ubo.handle, readback.handle};
  for (const object& o : world) buffers.insert(buffers.end(), {o.shape.vertices.handle, o.shape.indices.handle});
  for (VkBuffer b : buffers) vkDestroyBuffer(g.device, b, nullptr);
  close_gpu(g, mem);
  if (validation_messages) {
    std::fprintf(stderr, "engine_vk: %d validation messages\n", validation_messages);
    return 1;
  }
  if (!written) return 1;
  std::printf("engine_vk: step %d: %s\n", step, out.c_str());
  return 0;
}

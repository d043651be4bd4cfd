// Implements dstrans_vk_frame.hpp.
#include "dstrans_vk_frame.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <utility>

#include <dstrans/frame/culling.hpp>
#include <dstrans/frame/passes.hpp>
#include <dstrans/particles.hpp>

namespace dstrans::vk {

namespace {

using namespace dstrans::render;

constexpr std::uint32_t light_index_binding = 3;  // the renderer's instance-rate light index (location 3)
constexpr std::uint32_t texture_coordinates_location = 4;  // the engine's texture coordinates (vec2), with effect::textures
constexpr std::uint32_t texture_coordinates_binding = 4;   // vertex_input::streams(true)'s

// `st` without the texture coordinates' attribute, for a pipeline whose vertex shader does not read them.
pipeline_state without_texture_coordinates(pipeline_state st) {
  st.attributes.erase(std::remove_if(st.attributes.begin(), st.attributes.end(),
                                     [](const VkVertexInputAttributeDescription& a) { return a.location == texture_coordinates_location; }),
                      st.attributes.end());
  return st;
}

// Whether a pass of `step` calls the engine to draw its geometry.
bool draws_geometry(pass_step step) {
  return step == pass_step::gbuffer || step == pass_step::shadow || step == pass_step::ambient || step == pass_step::forward_light ||
         step == pass_step::capture;
}

struct compiled {
  const shader* vertex = nullptr;
  const shader* fragment = nullptr;  // or the compute shader
};

// A pipeline and the shaders its descriptor sets are filled for.
struct program {
  compiled stages;
  pipeline pipe;
};

// What a descriptor set binds: buffers, texel buffers, and sampled or storage images, by binding number.
struct bindings {
  std::map<int, VkBuffer> buffers;
  std::map<int, VkBufferView> texel_buffers;
  std::map<int, const image*> images;
  std::map<int, VkSampler> samplers;  // for sampled images not read with the nearest sampler
};

// The stages and accesses of a pass's reads and of its writes, by what kind of pass it is.
struct access {
  VkPipelineStageFlags stages = 0;
  VkAccessFlags mask = 0;
};
access reading(const scheduled_pass& p) {
  if (p.kind == pass_kind::dispatch) return {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT};
  if (p.kind == pass_kind::transfer) return {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT};
  return {VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT};
}
access writing(const scheduled_pass& p) {
  if (p.kind == pass_kind::dispatch)
    return {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
  if (p.kind == pass_kind::transfer) return {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT};
  // Attachments (blended: read too), storage written by fragments, and the clears a pass starts with.
  return {VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
              VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
          VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
              VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
              VK_ACCESS_TRANSFER_WRITE_BIT};
}

void memory_barrier(VkCommandBuffer cmd, access from, access to) {
  VkMemoryBarrier m{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  m.srcAccessMask = from.mask;
  m.dstAccessMask = to.mask;
  vkCmdPipelineBarrier(cmd, from.stages, to.stages, 0, 1, &m, 0, nullptr, 0, nullptr);
}

// An image a pass uses: the layout it needs the image in, and how the pass reaches it there.
struct image_use {
  VkImage handle = VK_NULL_HANDLE;
  VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
  VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL;
  access at;
};
VkImageAspectFlags aspect_of(const image& i) {
  return i.format == VK_FORMAT_D32_SFLOAT ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}
image_use attached(const image& i) {
  if (aspect_of(i) == VK_IMAGE_ASPECT_DEPTH_BIT)
    return {i.handle, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
            {VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
             VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT}};
  return {i.handle, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
          {VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT}};
}
image_use copied(const image& i, bool into) {
  return {i.handle, VK_IMAGE_ASPECT_COLOR_BIT, into ? VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
          {VK_PIPELINE_STAGE_TRANSFER_BIT, into ? VK_ACCESS_TRANSFER_WRITE_BIT : VK_ACCESS_TRANSFER_READ_BIT}};
}
// Adds `u` unless the pass uses its image already: attachments, added first, win over a sampled binding
// the shaders declare for the same image and do not read while they draw into it.
void add_use(std::vector<image_use>& into, const image_use& u) {
  for (const image_use& have : into)
    if (have.handle == u.handle) return;
  into.push_back(u);
}
void add_attachments(std::vector<image_use>& into, const vk::targets& t) {
  for (const image& c : t.colors) add_use(into, attached(c));
  if (t.depth.handle) add_use(into, attached(t.depth));
}

VkVertexInputAttributeDescription attribute(std::uint32_t location, std::uint32_t binding, VkFormat f, std::uint32_t offset = 0) {
  return {location, binding, f, offset};
}

std::vector<format> formats_of(const std::vector<target_desc>& targets) {
  std::vector<format> out;
  for (const target_desc& t : targets) out.push_back(t.fmt);
  return out;
}

std::vector<target_desc> shadow_targets(shadow_mode m) {
  return m == shadow_mode::transparent ? describe<thesis_shadow_map>() : describe<opaque_shadow_map>();
}

template <class T>
result<buffer> filled(device& dev, const std::vector<T>& data, VkBufferUsageFlags usage, const std::string& name) {
  auto b = dev.make_buffer(VkDeviceSize(std::max<std::size_t>(data.size(), 1) * sizeof(T)), usage, name);
  if (b && !data.empty()) std::memcpy(b->mapped, data.data(), data.size() * sizeof(T));
  return b;
}

}  // namespace

vertex_input vertex_input::streams(bool texture_coordinates) {
  vertex_input v;
  v.bindings = {{0, sizeof(glm::vec3), VK_VERTEX_INPUT_RATE_VERTEX},
                {1, sizeof(glm::vec3), VK_VERTEX_INPUT_RATE_VERTEX},
                {2, sizeof(std::uint32_t), VK_VERTEX_INPUT_RATE_VERTEX}};
  v.attributes = {attribute(0, 0, VK_FORMAT_R32G32B32_SFLOAT), attribute(1, 1, VK_FORMAT_R32G32B32_SFLOAT),
                  attribute(2, 2, VK_FORMAT_R32_UINT)};
  if (texture_coordinates) {
    v.bindings.push_back({texture_coordinates_binding, sizeof(glm::vec2), VK_VERTEX_INPUT_RATE_VERTEX});
    v.attributes.push_back(attribute(texture_coordinates_location, texture_coordinates_binding, VK_FORMAT_R32G32_SFLOAT));
  }
  return v;
}

struct renderer::impl {
  explicit impl(device& d) : dev(d) {}
  device& dev;
  scene description;  // without its meshes
  render::options o;
  frame_plan plan;
  particle_plan smoke;
  frame_schedule schedule;
  std::vector<light_block> light_data;  // light_blocks(description), computed once: it walks every vertex
  vertex_input vertices;
  int slots = 2;

  program gbuffer[2], shadow, shadow_depth, light[3][2], ambient, forward_light[3], compose, compose_still, capture, resolve, particle, bake[2];
  std::vector<program> post;

  std::vector<buffer> owned;  // every buffer made once
  buffer light_index, sphere_vertices, sphere_indices, cone_vertices, cone_indices, materials, lights, regions, unshadowed, bake_regions;
  VkBufferView material_texels = VK_NULL_HANDLE;  // `materials` as RGBA32F texels (slot::materials)
  std::size_t sphere_count = 0, cone_count = 0;
  std::vector<buffer> post_blocks, camera_blocks, quads;  // the last two: one a frame in flight
  std::vector<std::size_t> quad_counts;
  std::map<int, buffer> shadowed_lights;                 // by light
  std::map<int, std::vector<buffer>> light_blocks_by_light;  // by light, a block for each view of its shadow map
  std::map<int, std::uint32_t> shadow_layer_of;                  // by light
  vk::targets shadow_map;
  int pictured_light = -1;
  image shadow_layers[2];
  image material_textures;  // effect::textures: the scene's textures as one array
  // The sampler of the material textures; the binding of the renderer's (0, 0) texture coordinates for an
  // engine whose vertices have none (-1: they have them, or nothing samples textures).
  VkSampler sampler = VK_NULL_HANDLE, linear_sampler = VK_NULL_HANDLE, texture_sampler = VK_NULL_HANDLE;
  int zero_uv_binding = -1;
  buffer zero_uv;

  frame_targets out;
  vk::targets tail, glass_layers, lit_colour_only;  // the last: a view of the forward target's colour and depth (owns nothing)
  VkDescriptorPool pool = VK_NULL_HANDLE;
  std::vector<std::vector<VkDescriptorSet>> sets;  // [frame in flight][pass]

  VkQueryPool queries = VK_NULL_HANDLE;
  std::uint32_t queries_per_frame = 0;
  double timestamp_ns = 1.0;
  int frames_recorded = 0, last_slot = -1;
  struct state {
    access write, reads;  // the last write, and the reads after it
  };
  std::map<std::string, state> states;
  // Where an image is: its layout, and every access since it entered it (which its next transition waits for).
  struct image_state {
    VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL;  // the device makes images in GENERAL
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    access since;
  };
  std::map<VkImage, image_state> layouts;
  std::vector<std::vector<image_use>> uses;  // by pass: the images it draws into, samples, stores to or copies
  // The frame's opening clears (frame_schedule::cleared), each as the pass the barriers see.
  struct frame_clear {
    scheduled_pass pass;
    const vk::targets* light_buffer;  // null: the volume atlas
    std::vector<image_use> images;
    std::vector<glm::vec4> zeros;  // one a light-buffer target
  };
  std::vector<frame_clear> clears;
  // Temporal interlacing: the frames recorded into these targets since they were made, the last one's
  // block (while a frame is recorded, that frame's), and the sets, uses and clears of the next frame, which
  // draws into the other G-buffer.
  std::uint64_t sequence = 0;
  frame_block previous{};
  std::vector<std::vector<VkDescriptorSet>> swapped_sets;
  std::vector<std::vector<image_use>> swapped_uses;
  std::vector<frame_clear> swapped_clears;
  // What settle and rest build, kept so that recording a frame allocates nothing.
  std::vector<VkImageMemoryBarrier> moves;
  std::vector<image_use> resting;

  ~impl();
  result<compiled> compile(const result<pass_sources>& p, const std::string& name);
  result<bool> graphics(program& into, const result<pass_sources>& p, const std::vector<format>& formats, const std::string& name,
                        const pipeline_state& st = {});
  result<bool> make_pipelines(const pass_shaders& sh, const std::vector<format>& gbuffer_formats, const std::vector<format>& light_formats,
                              const std::vector<format>& lit_formats, const std::vector<format>& final_formats);
  result<bool> make_fixed();
  result<bool> make_particles();
  result<bool> make_shadow_layers();
  result<bool> make_sized();
  void destroy_sized();
  result<bool> make_sets();
  result<bool> fill_sets();
  result<VkDescriptorSet> make_set(const program& p, const bindings& b, access reads, std::vector<image_use>& used);
  const vk::targets* attachments(const scheduled_pass& pass) const;
  std::vector<image_use> copies(const scheduled_pass& pass) const;
  bindings bindings_of(const scheduled_pass& pass, int slot) const;
  const program& program_of(const scheduled_pass& pass) const;

  void barrier(VkCommandBuffer cmd, const scheduled_pass& pass, const std::vector<image_use>& images);
  void settle(VkCommandBuffer cmd, access from, access to, const std::vector<image_use>& images);
  void rest(VkCommandBuffer cmd);
  void run(VkCommandBuffer cmd, const scheduled_pass& pass, VkDescriptorSet set, int slot, const draw_geometry& draw);
  void copy_shadow_picture(VkCommandBuffer cmd);
  void swap_layers();
};

renderer::impl::~impl() {
  const VkDevice d = dev.ctx().device;
  const VkAllocationCallbacks* a = dev.ctx().allocator;
  destroy_sized();
  if (queries) vkDestroyQueryPool(d, queries, a);
  if (sampler) vkDestroySampler(d, sampler, a);
  if (material_texels) vkDestroyBufferView(d, material_texels, a);
  if (linear_sampler) vkDestroySampler(d, linear_sampler, a);
  if (texture_sampler) vkDestroySampler(d, texture_sampler, a);
  dev.destroy(material_textures);
  dev.destroy(shadow_map);
  dev.destroy(out.volume_atlas);
  for (image& i : shadow_layers) dev.destroy(i);
  for (buffer& b : owned) dev.destroy(b);
  for (program* p : {&gbuffer[0], &gbuffer[1], &shadow, &shadow_depth, &ambient, &compose, &compose_still, &capture, &resolve, &particle, &bake[0], &bake[1]}) dev.destroy(p->pipe);
  for (auto& row : light) for (program& p : row) dev.destroy(p.pipe);
  for (program& p : forward_light) dev.destroy(p.pipe);
  for (program& p : post) dev.destroy(p.pipe);
}

result<compiled> renderer::impl::compile(const result<pass_sources>& p, const std::string& name) {
  if (!p) return failure{p.error()};
  auto v = dev.get_shader(p->vertex, spirv::stage::vertex, name + " (vertex)");
  if (!v) return failure{v.error()};
  auto f = dev.get_shader(p->fragment, spirv::stage::fragment, name + " (fragment)");
  if (!f) return failure{f.error()};
  return compiled{*v, *f};
}

result<bool> renderer::impl::graphics(program& into, const result<pass_sources>& p, const std::vector<format>& formats,
                                      const std::string& name, const pipeline_state& st) {
  auto sh = compile(p, name);
  if (!sh) return failure{sh.error()};
  auto pipe = dev.make_graphics_pipeline(*sh->vertex, *sh->fragment, formats, name, st);
  if (!pipe) return failure{pipe.error()};
  into = {*sh, *pipe};
  return true;
}

result<bool> renderer::impl::make_pipelines(const pass_shaders& sh, const std::vector<format>& gbuffer_formats,
                                            const std::vector<format>& light_formats, const std::vector<format>& lit_formats,
                                            const std::vector<format>& final_formats) {
  const shadow_mode mode = plan.shadows;
  pipeline_state scene_state;
  scene_state.bindings = vertices.bindings;
  scene_state.attributes = vertices.attributes;
  if (zero_uv_binding >= 0) {
    // Every vertex reads the one (0, 0) of the renderer's buffer.
    scene_state.bindings.push_back({std::uint32_t(zero_uv_binding), 0, VK_VERTEX_INPUT_RATE_VERTEX});
    scene_state.attributes.push_back(attribute(texture_coordinates_location, std::uint32_t(zero_uv_binding), VK_FORMAT_R32G32_SFLOAT));
  }
  if (!plan.on.has(effect::textures)) scene_state = without_texture_coordinates(scene_state);
  scene_state.depth_attachment = scene_state.depth_test = scene_state.depth_write = true;
  // The forward passes read the light's index per instance, as the light volumes do.
  pipeline_state forward_state = scene_state;
  forward_state.bindings.push_back({light_index_binding, sizeof(std::uint32_t), VK_VERTEX_INPUT_RATE_INSTANCE});
  forward_state.attributes.push_back(attribute(3, light_index_binding, VK_FORMAT_R32_UINT));
  // Where the resolve and the particles draw: the composed frame, or the glass layers around the glass.
  const std::vector<format> layered_formats = plan.around_glass ? formats_of(glass_layer_targets()) : final_formats;
  std::vector<result<bool>> made;
  for (int k = 0; k < plan.layers; ++k)
    made.push_back(graphics(gbuffer[k], gbuffer_pass(sh, plan.peeling ? (k ? layer::second : layer::first) : layer::interlaced, plan.on, o),
                            gbuffer_formats, "gbuffer pass", scene_state));
  // Shadow passes cull the back faces of closed objects (scene_geometry, pass_state::cull_closed).
  pipeline_state shadow_state = scene_state;
  shadow_state.dynamic_cull = true;
  if (mode != shadow_mode::off)
    made.push_back(graphics(shadow, shadow_pass(sh, mode, plan.shadow_effects()), formats_of(shadow_targets(mode)), "shadow pass",
                            plan.textured_shadows ? shadow_state : without_texture_coordinates(shadow_state)));
  if (plan.depth_only_shadows)
    made.push_back(graphics(shadow_depth, shadow_pass(sh, mode, effects{}, true), formats_of(shadow_targets(mode)),
                            "shadow pass, opaque surfaces", without_texture_coordinates(shadow_state)));
  for (shadow_mode k : all_lookups)
    for (int vol = 0; vol < 2 && !plan.forward && plan.uses(k); ++vol) {
      // Volumes are drawn with their back faces, depth clamped (dstrans/frame/plan.hpp, volume).
      pipeline_state st;
      st.additive = true;
      st.bindings.push_back({light_index_binding, sizeof(std::uint32_t), VK_VERTEX_INPUT_RATE_INSTANCE});
      st.attributes.push_back(attribute(3, light_index_binding, VK_FORMAT_R32_UINT));
      if (vol) {
        st.bindings.push_back({0, sizeof(glm::vec3), VK_VERTEX_INPUT_RATE_VERTEX});
        st.attributes.push_back(attribute(0, 0, VK_FORMAT_R32G32B32_SFLOAT));
        st.cull = VK_CULL_MODE_FRONT_BIT;
        st.depth_clamp = true;
      }
      made.push_back(graphics(light[int(k)][vol], light_pass(sh, k, vol == 1, o), light_formats,
                              std::string("light pass") + lookup_label(k) + (vol ? " volume" : " fullscreen"), st));
    }
  if (plan.forward) {
    made.push_back(graphics(ambient, forward_pass(sh, forward_stage::ambient, plan.forward_depth, shadow_mode::off, plan.on), lit_formats,
                            "forward ambient pass", forward_state));
    pipeline_state st = forward_state;
    st.depth_write = false;
    st.depth_compare = VK_COMPARE_OP_LESS_OR_EQUAL;
    st.additive = true;
    for (shadow_mode k : all_lookups)
      if (plan.uses(k))
        made.push_back(graphics(forward_light[int(k)], forward_pass(sh, forward_stage::light, plan.forward_depth, k, plan.on, o),
                                {lit_formats[0]}, std::string("forward light pass") + lookup_label(k), st));
  }
  made.push_back(graphics(compose, plan.forward ? forward_pass(sh, forward_stage::blend, plan.forward_depth, shadow_mode::off, plan.on)
                                                : compose_pass(sh, plan.on, o),
                          final_formats, plan.forward ? "forward blend pass" : "compose pass"));
  if (plan.temporal) made.push_back(graphics(compose_still, compose_pass(sh, plan.on, o, true), final_formats, "compose pass still camera"));
  if (plan.lists) {
    // Hair takes its factors alone; the exact reference's glass samples its textures.
    pipeline_state st = plan.exact ? scene_state : without_texture_coordinates(scene_state);
    st.additive = true;
    made.push_back(graphics(capture, capture_pass(sh, mode, o, plan.around_glass, plan.on), formats_of(kbuffer_tail_targets()), "capture pass", st));
    pipeline_state rs;
    rs.transmit = true;
    rs.transmit_alpha = plan.around_glass;
    made.push_back(graphics(resolve, resolve_pass(sh, mode, o, plan.around_glass), layered_formats, "resolve pass", rs));
  }
  if (smoke.on) {
    for (const int shadowed : {0, 1}) {
      if (!smoke.baking || (shadowed ? smoke.shadowed_lights.empty() : smoke.unshadowed_lights.empty())) continue;
      const std::string name = shadowed ? "bake pass shadowed" : "bake pass";
      auto src = bake_pass(sh, shadowed ? mode : shadow_mode::off, o);
      if (!src) return failure{src.error()};
      auto c = dev.get_shader(*src, spirv::stage::compute, name);
      if (!c) return failure{c.error()};
      auto p = dev.make_compute_pipeline(**c, name);
      if (!p) return failure{p.error()};
      bake[shadowed] = {{nullptr, *c}, *p};
    }
    pipeline_state st;
    st.transmit = !plan.exact;  // colour premultiplied, and in alpha what the frame behind keeps
    st.transmit_alpha = plan.around_glass;
    st.additive = plan.exact;  // the exact reference's into the lists, their overflow added to the tail
    st.bindings = {{0, sizeof(particle_vertex), VK_VERTEX_INPUT_RATE_VERTEX}};
    st.attributes = {attribute(0, 0, VK_FORMAT_R32G32B32_SFLOAT, std::uint32_t(offsetof(particle_vertex, position))),
                     attribute(1, 0, VK_FORMAT_R32_UINT, std::uint32_t(offsetof(particle_vertex, system))),
                     attribute(2, 0, VK_FORMAT_R32G32B32A32_SFLOAT, std::uint32_t(offsetof(particle_vertex, corner)))};
    made.push_back(graphics(particle, particle_pass(sh, smoke.shadows, o, plan.around_glass),
                            plan.exact ? formats_of(kbuffer_tail_targets()) : layered_formats, "particle pass", st));
  }
  post.resize(plan.post.passes.size());
  for (std::size_t k = 0; k < post.size(); ++k)
    made.push_back(graphics(post[k], post_pass_sources(sh, plan.post.passes[k], o), final_formats, "post " + plan.post.passes[k].name));
  for (const result<bool>& m : made)
    if (!m) return m;
  return true;
}


result<bool> renderer::impl::make_fixed() {
  const VkBufferUsageFlags vertex_use = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, index_use = VK_BUFFER_USAGE_INDEX_BUFFER_BIT,
                           uniform_use = VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, storage_use = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  std::vector<std::uint32_t> light_ids(description.lights.size());
  for (std::size_t i = 0; i < light_ids.size(); ++i) light_ids[i] = std::uint32_t(i);
  const mesh_data sphere = sphere_mesh(1), cone = cone_mesh(16);
  sphere_count = sphere.indices.size();
  cone_count = cone.indices.size();
  std::vector<std::pair<buffer*, result<buffer>>> made;
  made.emplace_back(&light_index, filled(dev, light_ids, vertex_use, "light indices"));
  made.emplace_back(&sphere_vertices, filled(dev, sphere.positions, vertex_use, "point light volume"));
  made.emplace_back(&sphere_indices, filled(dev, sphere.indices, index_use, "point light volume"));
  made.emplace_back(&cone_vertices, filled(dev, cone.positions, vertex_use, "spot light volume"));
  made.emplace_back(&cone_indices, filled(dev, cone.indices, index_use, "spot light volume"));
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(dev.ctx().physical_device, &props);
  timestamp_ns = double(props.limits.timestampPeriod);
  if (auto ok = materials_fit(description, props.limits.maxTexelBufferElements); !ok) return ok;
  made.emplace_back(&materials, filled(dev, material_blocks(description), VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, "materials"));
  if (zero_uv_binding >= 0) made.emplace_back(&zero_uv, filled(dev, std::vector<glm::vec2>{glm::vec2(0.0f)}, vertex_use, "zero texture coordinates"));
  made.emplace_back(&lights, filled(dev, light_data, storage_use, "lights"));
  camera_blocks.resize(std::size_t(slots));
  for (buffer& b : camera_blocks) made.emplace_back(&b, filled(dev, std::vector<frame_block>{camera_frame(description, o)}, uniform_use, "camera frame"));
  for (std::size_t i = 0; i < description.lights.size(); ++i)
    if (plan.lookups[i] != shadow_mode::off) {
      std::vector<buffer>& views = light_blocks_by_light[int(i)];
      views.resize(std::size_t(shadow_views(light_data[i])));
      for (std::size_t v = 0; v < views.size(); ++v)
        made.emplace_back(&views[v], filled(dev, std::vector<frame_block>{light_frame(description, light_data[i], o, int(v))}, uniform_use,
                                            "light frame"));
    }
  post_blocks.resize(plan.post.passes.size());
  for (std::size_t k = 0; k < post_blocks.size(); ++k) {
    const post_pass& pass = plan.post.passes[k];
    made.emplace_back(&post_blocks[k], filled(dev, std::vector<glm::vec4>{glm::vec4(pass.params[0], pass.params[1], pass.params[2], pass.params[3])},
                                              uniform_use, "post " + pass.name));
  }
  for (auto& [into, b] : made) {
    if (!b) return failure{b.error()};
    *into = *b;
    owned.push_back(*b);
  }
  VkBufferViewCreateInfo texels{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
  texels.buffer = materials.handle;
  texels.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  texels.range = VK_WHOLE_SIZE;
  if (vkCreateBufferView(dev.ctx().device, &texels, dev.ctx().allocator, &material_texels) != VK_SUCCESS)
    return failure{"cannot create the materials' texel view"};
  if (plan.shadows != shadow_mode::off) {
    auto sm = dev.make_targets(shadow_targets(plan.shadows), o.shadow_size, o.shadow_size, "shadow map", true);
    if (!sm) return failure{sm.error()};
    shadow_map = *sm;
    for (std::size_t i = 0; i < plan.lookups.size() && pictured_light < 0; ++i)
      if (plan.lookups[i] != shadow_mode::off) pictured_light = int(i);
    if (plan.shadows == shadow_mode::transparent && pictured_light >= 0) {
      auto b = dev.make_buffer(VkDeviceSize(o.shadow_size) * VkDeviceSize(o.shadow_size) * 4u, VK_BUFFER_USAGE_TRANSFER_DST_BIT, "shadow picture");
      if (!b) return failure{b.error()};
      out.shadow_picture = *b;
      owned.push_back(*b);
    }
  }
  VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  vkCreateSampler(dev.ctx().device, &sci, dev.ctx().allocator, &sampler);
  sci.magFilter = sci.minFilter = VK_FILTER_LINEAR;  // the volume atlas is read trilinearly
  vkCreateSampler(dev.ctx().device, &sci, dev.ctx().allocator, &linear_sampler);
  if (plan.on.has(effect::textures)) {
    // Repeating and trilinear: the shader wraps each texture as it says (dst_wrap).
    sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    sci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    sci.maxLod = VK_LOD_CLAMP_NONE;
    vkCreateSampler(dev.ctx().device, &sci, dev.ctx().allocator, &texture_sampler);
    auto t = dev.make_texture_array(texture_array_of(description), "material textures");
    if (!t) return failure{t.error()};
    material_textures = *t;
  }
  // Two timestamps a pass and two for the whole frame, a frame in flight each.
  queries_per_frame = std::uint32_t(2 * schedule.passes.size() + 2);
  VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  qci.queryType = VK_QUERY_TYPE_TIMESTAMP;
  qci.queryCount = queries_per_frame * std::uint32_t(slots);
  if (vkCreateQueryPool(dev.ctx().device, &qci, dev.ctx().allocator, &queries) != VK_SUCCESS) return failure{"no timestamp query pool"};
  dev.name(VK_OBJECT_TYPE_QUERY_POOL, std::uint64_t(queries), "frame timestamps");
  if (plan.shadow_layers)
    if (auto ok = make_shadow_layers(); !ok) return ok;
  return smoke.on ? make_particles() : result<bool>(true);
}

// The atlas (the bake adds into it, the particles sample it), each region's bake block, the lights per
// dispatch; the particles' regions and quads.
result<bool> renderer::impl::make_particles() {
  const volume_atlas& a = smoke.atlas;
  const VkBufferUsageFlags storage_use = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  std::vector<std::pair<buffer*, result<buffer>>> made;
  made.emplace_back(&unshadowed, filled(dev, smoke.unshadowed_lights, storage_use, "volume lights"));
  made.emplace_back(&regions, filled(dev, particle_regions(description, smoke), storage_use, "particle regions"));
  made.emplace_back(&bake_regions, filled(dev, bake_blocks(a, smoke.ranges), storage_use, "volume regions"));
  for (const volume_light& l : smoke.shadowed_lights) {
    const int i = int(l.cos_inner.y);
    made.emplace_back(&shadowed_lights[i], filled(dev, std::vector<volume_light>{l}, storage_use, "volume light " + std::to_string(i)));
  }
  std::size_t count = 0;
  for (const particle_system& ps : description.particles) count += std::size_t(std::max(ps.count, 0));
  quads.resize(std::size_t(slots));
  quad_counts.assign(std::size_t(slots), 0);
  for (buffer& q : quads) made.emplace_back(&q, filled(dev, std::vector<particle_vertex>(count * 6), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "particle quads"));
  for (auto& [into, b] : made) {
    if (!b) return failure{b.error()};
    *into = *b;
    owned.push_back(*b);
  }
  if (smoke.baking) {
    const glm::ivec3 size = glm::max(a.size, glm::ivec3(1));  // a forced effect with no system
    auto img = dev.make_sampled_image(VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_VIEW_TYPE_3D, size.x, size.y, size.z, "volume atlas", true);
    if (!img) return failure{img.error()};
    out.volume_atlas = *img;
    out.volume_atlas_size = size;
  }
  return true;
}

// The shadow maps' layers (frame_plan::shadow_layers), one a shadowed light in light order.
result<bool> renderer::impl::make_shadow_layers() {
  for (std::size_t t = 0; t < shadow_map.colors.size(); ++t) {
    auto img = dev.make_sampled_image(VkFormat(info(shadow_map.formats[t]).vk_format), VK_IMAGE_VIEW_TYPE_2D_ARRAY, o.shadow_size,
                                      o.shadow_size, int(smoke.shadowed_lights.size()), t ? "shadow layers colour" : "shadow layers depth");
    if (!img) return failure{img.error()};
    shadow_layers[t] = *img;
  }
  for (std::size_t k = 0; k < smoke.shadowed_lights.size(); ++k) shadow_layer_of[int(smoke.shadowed_lights[k].cos_inner.y)] = std::uint32_t(k);
  return true;
}

result<bool> renderer::impl::make_sized() {
  for (int k = 0; k < plan.kept_layers(); ++k) {
    const std::string suffix = k ? " 2" : "";
    auto g = dev.make_targets(gbuffer_targets(o.layout), o.width, o.height, "gbuffer" + suffix, true);
    if (!g) return failure{g.error()};
    out.gbuffers.push_back(*g);
    auto l = dev.make_targets(light_targets(o), o.width, o.height, "light buffer" + suffix, false);
    if (!l) return failure{l.error()};
    out.light_buffers.push_back(*l);
  }
  if (plan.forward) {
    auto t = dev.make_targets(forward_targets(plan.forward_depth, o.float_targets), o.width, o.height, "forward", true);
    if (!t) return failure{t.error()};
    out.lit = *t;
    lit_colour_only = vk::targets{{out.lit.colors[0]}, {out.lit.formats[0]}, out.lit.depth, out.lit.width, out.lit.height};
  }
  auto composed = dev.make_targets({final_target_desc(o.float_targets)}, o.width, o.height, "final", false);
  if (!composed) return failure{composed.error()};
  out.composed = *composed;
  for (const std::string& name : plan.post.targets) {
    auto t = dev.make_targets({final_target_desc(o.float_targets)}, o.width, o.height, "post " + name, false);
    if (!t) return failure{t.error()};
    out.post[name] = *t;
  }
  out.output = plan.post.passes.empty() ? &out.composed : &out.post.at(plan.post.output);
  if (plan.lists) {
    auto t = dev.make_targets(kbuffer_tail_targets(), o.width, o.height, "k-buffer tail", false);
    if (!t) return failure{t.error()};
    tail = *t;
    auto heads = dev.make_storage_image(VK_FORMAT_R32_UINT, o.width, o.height, "k-buffer heads");
    if (!heads) return failure{heads.error()};
    out.kbuffer_heads = *heads;
    out.kbuffer_capacity = kbuffer_capacity(o);
    auto nodes = dev.make_buffer((VkDeviceSize(out.kbuffer_capacity) + 1u) * 16u,
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, "k-buffer nodes");
    if (!nodes) return failure{nodes.error()};
    out.kbuffer_nodes = *nodes;
  }
  if (plan.around_glass) {
    auto t = dev.make_targets(glass_layer_targets(), o.width, o.height, "glass layers", false);
    if (!t) return failure{t.error()};
    glass_layers = *t;
  }
  return make_sets();
}

void renderer::impl::destroy_sized() {
  // Their handles may come back for other images.
  auto forget = [&](const vk::targets& t) {
    for (const image& c : t.colors) layouts.erase(c.handle);
    layouts.erase(t.depth.handle);
  };
  for (const vk::targets* t : {&out.lit, &out.composed, &tail, &glass_layers}) forget(*t);
  for (const vk::targets& t : out.gbuffers) forget(t);
  for (const vk::targets& t : out.light_buffers) forget(t);
  for (const auto& [name, t] : out.post) forget(t);
  layouts.erase(out.kbuffer_heads.handle);
  for (vk::targets* t : {&out.lit, &out.composed, &tail, &glass_layers}) dev.destroy(*t);
  for (vk::targets& t : out.gbuffers) dev.destroy(t);
  for (vk::targets& t : out.light_buffers) dev.destroy(t);
  for (auto& [name, t] : out.post) dev.destroy(t);
  out.gbuffers.clear();
  out.light_buffers.clear();
  out.post.clear();
  out.output = nullptr;
  dev.destroy(out.kbuffer_heads);
  dev.destroy(out.kbuffer_nodes);
  lit_colour_only = {};
  if (pool) vkDestroyDescriptorPool(dev.ctx().device, pool, dev.ctx().allocator);
  pool = VK_NULL_HANDLE;
  sets.clear();
  swapped_sets.clear();
  states.clear();  // new images: nothing to wait for
  sequence = 0;    // and no previous frame
}

// The G-buffer and light buffer a frame draws into become the previous frame's, which the compose pass
// reads, and the other pair the next frame's, with the sets, uses and clears made for that order.
void renderer::impl::swap_layers() {
  std::swap(out.gbuffers[0], out.gbuffers[1]);
  std::swap(out.light_buffers[0], out.light_buffers[1]);
  std::swap(sets, swapped_sets);
  std::swap(uses, swapped_uses);
  std::swap(clears, swapped_clears);
}

const program& renderer::impl::program_of(const scheduled_pass& pass) const {
  const std::size_t i = std::size_t(std::max(pass.light, 0));
  switch (pass.step) {
    case pass_step::gbuffer: return gbuffer[pass.index];
    case pass_step::ambient: return ambient;
    case pass_step::shadow: return pass.draws == geometry_set::opaque ? shadow_depth : shadow;
    case pass_step::light: return light[int(plan.lookups[i])][pass.kind == pass_kind::light_volume ? 1 : 0];
    case pass_step::forward_light: return forward_light[int(plan.lookups[i])];
    case pass_step::bake: return bake[0];
    case pass_step::bake_light: return bake[1];
    case pass_step::compose:
    case pass_step::blend: return compose;
    case pass_step::capture: return capture;
    case pass_step::resolve: return resolve;
    case pass_step::particles: return particle;
    case pass_step::post: return post[std::size_t(pass.index)];
    case pass_step::shadow_layer: break;
  }
  static const program none;  // transfers bind nothing
  return none;
}

// What `pass` binds in frame-in-flight `slot`: the frame's blocks (a shadow pass: its light's view), the
// shadow map, the G-buffer of the layer it serves, and what its step reads besides. A set is filled from
// this by what its shaders declare.
bindings renderer::impl::bindings_of(const scheduled_pass& pass, int slot) const {
  bindings b;
  b.buffers = {{binding(slot::frame), camera_blocks[std::size_t(slot)].handle}, {binding(slot::lights), lights.handle}};
  b.texel_buffers = {{binding(slot::materials), material_texels}};
  if (pass.step == pass_step::shadow)
    b.buffers[binding(slot::frame)] = light_blocks_by_light.at(pass.light).at(std::size_t(pass.index)).handle;
  if (material_textures.view) {
    b.images[binding(slot::material_textures)] = &material_textures;
    b.samplers[binding(slot::material_textures)] = texture_sampler;
  }
  for (std::size_t t = 0; t < shadow_map.colors.size(); ++t) b.images[binding(slot::shadow_map) + int(t)] = &shadow_map.colors[t];
  // A G-buffer's images at `first` and up (the compact layout's depth attachment at its depth slot).
  auto add_gbuffer = [&](int first, const vk::targets& g) {
    for (std::size_t t = 0; t < g.colors.size(); ++t) b.images[first + int(t)] = &g.colors[t];
    if (o.layout == gbuffer_layout::compact) b.images[first + gbuffer_depth_slot] = &g.depth;
  };
  if (!plan.forward) {
    const std::size_t layer = pass.step == pass_step::light ? std::size_t(pass.index) : 0;
    add_gbuffer(binding(slot::gbuffer), out.gbuffers[layer]);
    for (std::size_t t = 0; t < out.light_buffers[layer].colors.size(); ++t)
      b.images[binding(slot::light) + int(t)] = &out.light_buffers[layer].colors[t];
    b.images[binding(slot::peel_depth)] = o.layout == gbuffer_layout::compact ? &out.gbuffers[0].depth : &out.gbuffers[0].colors[3];
  }
  if (plan.kept_layers() == 2) {  // peeling's second layer, or the previous frame's
    add_gbuffer(binding(slot::gbuffer2), out.gbuffers[1]);
    for (std::size_t t = 0; t < out.light_buffers[1].colors.size(); ++t)
      b.images[binding(slot::light2) + int(t)] = &out.light_buffers[1].colors[t];
  }
  for (std::size_t t = 0; t < out.lit.colors.size(); ++t) b.images[binding(slot::forward_lit) + int(t)] = &out.lit.colors[t];
  if (out.kbuffer_heads.view) {
    b.images[binding(slot::kbuffer_heads)] = &out.kbuffer_heads;
    b.buffers[binding(slot::kbuffer_nodes)] = out.kbuffer_nodes.handle;
    for (int t = 0; t < 2; ++t) b.images[binding(slot::kbuffer_tail) + t] = &tail.colors[std::size_t(t)];
  }
  for (std::size_t t = 0; t < glass_layers.colors.size(); ++t) b.images[binding(slot::glass_layers) + int(t)] = &glass_layers.colors[t];
  if (smoke.on) {
    b.buffers[binding(slot::particle_regions)] = regions.handle;
    b.buffers[binding(slot::volume_lights)] = pass.step == pass_step::bake_light ? shadowed_lights.at(pass.light).handle : unshadowed.handle;
    b.buffers[binding(slot::volume_regions)] = bake_regions.handle;
    if (out.volume_atlas.view) {
      b.images[binding(slot::volume_image)] = &out.volume_atlas;
      b.images[binding(slot::volume_atlas)] = &out.volume_atlas;
      b.samplers[binding(slot::volume_atlas)] = linear_sampler;
    }
  }
  for (int t = 0; t < 2; ++t)
    if (shadow_layers[t].view) b.images[binding(slot::shadow_layers) + t] = &shadow_layers[t];
  if (pass.step == pass_step::post) {
    const post_pass& p = plan.post.passes[std::size_t(pass.index)];
    b.buffers[binding(slot::post_params)] = post_blocks[std::size_t(pass.index)].handle;
    int input = binding(slot::post_input);
    for (const std::string& in : p.inputs)
      if (in != "gbuffer") b.images[input++] = in == "frame" ? &out.composed.colors[0] : &out.post.at(in).colors[0];
  }
  return b;
}

// A descriptor set for `p`, filled from `b` by what its shaders declare; the images it binds join `used`,
// sampled ones in SHADER_READ_ONLY_OPTIMAL (read as `reads`), storage ones in GENERAL.
result<VkDescriptorSet> renderer::impl::make_set(const program& p, const bindings& b, access reads, std::vector<image_use>& used) {
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &p.pipe.set_layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  if (vkAllocateDescriptorSets(dev.ctx().device, &ai, &set) != VK_SUCCESS) return failure{"descriptor pool exhausted"};
  std::vector<VkWriteDescriptorSet> writes;
  std::vector<VkDescriptorBufferInfo> buffer_infos;
  std::vector<VkDescriptorImageInfo> image_infos;
  buffer_infos.reserve(64);
  image_infos.reserve(64);
  std::map<int, bool> done;
  auto write = [&](int at, VkDescriptorType type) -> result<bool> {
    if (done[at]) return true;
    done[at] = true;
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = set;
    w.dstBinding = std::uint32_t(at);
    w.descriptorCount = 1;
    w.descriptorType = type;
    if (type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER || type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE) {
      const auto it = b.images.find(at);
      if (it == b.images.end()) return failure{"nothing bound to image binding " + std::to_string(at)};
      const bool sampled = type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
      const auto own = b.samplers.find(at);
      const image& img = *it->second;
      const VkImageLayout layout = sampled ? VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_GENERAL;
      const access stored{reads.stages, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
      add_use(used, {img.handle, aspect_of(img), layout, sampled ? reads : stored});
      image_infos.push_back({!sampled ? VK_NULL_HANDLE : own != b.samplers.end() ? own->second : sampler, img.view, layout});
      w.pImageInfo = &image_infos.back();
    } else if (type == VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER) {
      const auto it = b.texel_buffers.find(at);
      if (it == b.texel_buffers.end()) return failure{"nothing bound to texel buffer binding " + std::to_string(at)};
      w.pTexelBufferView = &it->second;
    } else {
      const auto it = b.buffers.find(at);
      if (it == b.buffers.end()) return failure{"nothing bound to buffer binding " + std::to_string(at)};
      buffer_infos.push_back({it->second, 0, VK_WHOLE_SIZE});
      w.pBufferInfo = &buffer_infos.back();
    }
    writes.push_back(w);
    return true;
  };
  for (const shader* s : {p.stages.vertex, p.stages.fragment}) {
    if (!s) continue;
    for (const auto& res : s->reflection.samplers)
      if (auto ok = write(res.binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER); !ok) return failure{ok.error()};
    for (const auto& res : s->reflection.uniform_buffers)
      if (auto ok = write(res.binding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER); !ok) return failure{ok.error()};
    for (const auto& res : s->reflection.storage_buffers)
      if (auto ok = write(res.binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER); !ok) return failure{ok.error()};
    for (const auto& res : s->reflection.storage_images)
      if (auto ok = write(res.binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE); !ok) return failure{ok.error()};
    for (const auto& res : s->reflection.texel_buffers)
      if (auto ok = write(res.binding, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER); !ok) return failure{ok.error()};
  }
  vkUpdateDescriptorSets(dev.ctx().device, std::uint32_t(writes.size()), writes.data(), 0, nullptr);
  return set;
}

// Every pass's set, a frame in flight each; with temporal interlacing also for the G-buffers swapped.
result<bool> renderer::impl::make_sets() {
  std::uint32_t count = 0;
  for (const scheduled_pass& pass : schedule.passes)
    count += pass.kind == pass_kind::transfer ? 0u : 1u;
  count = std::max(count, 1u) * std::uint32_t(slots) * (plan.temporal ? 2u : 1u);
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 4 * count},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 8 * count},
                                        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16 * count},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2 * count},
                                        {VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, count}};
  VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pci.maxSets = count;
  pci.poolSizeCount = std::uint32_t(std::size(sizes));
  pci.pPoolSizes = sizes;
  if (vkCreateDescriptorPool(dev.ctx().device, &pci, dev.ctx().allocator, &pool) != VK_SUCCESS) return failure{"no descriptor pool"};
  if (plan.temporal) {
    std::swap(out.gbuffers[0], out.gbuffers[1]);
    std::swap(out.light_buffers[0], out.light_buffers[1]);
    auto ok = fill_sets();
    swap_layers();  // the targets back, what was made for them aside
    if (!ok) return ok;
  }
  return fill_sets();
}

// The sets, image uses and clears of a frame that draws into out.gbuffers[0] and out.light_buffers[0].
result<bool> renderer::impl::fill_sets() {
  sets.assign(std::size_t(slots), std::vector<VkDescriptorSet>(schedule.passes.size(), VK_NULL_HANDLE));
  uses.assign(schedule.passes.size(), {});
  clears.clear();
  for (const std::string& name : schedule.cleared) {
    const bool atlas = name == "volume atlas";
    frame_clear c{scheduled_pass("", "clear " + name, atlas ? pass_kind::transfer : pass_kind::fullscreen, -1, {}, {name}),
                  atlas ? nullptr : &out.light_buffers[name == "light buffer" ? 0 : 1], {}, {}};
    if (atlas) c.images.push_back(copied(out.volume_atlas, true));
    if (c.light_buffer) {
      add_attachments(c.images, *c.light_buffer);
      c.zeros.assign(c.light_buffer->colors.size(), glm::vec4(0.0f));
    }
    clears.push_back(std::move(c));
  }
  for (std::size_t k = 0; k < schedule.passes.size(); ++k) {
    if (const vk::targets* t = attachments(schedule.passes[k])) add_attachments(uses[k], *t);
    for (const image_use& u : copies(schedule.passes[k])) add_use(uses[k], u);
  }
  for (int slot = 0; slot < slots; ++slot)
    for (std::size_t k = 0; k < schedule.passes.size(); ++k) {
      const scheduled_pass& pass = schedule.passes[k];
      if (pass.kind == pass_kind::transfer) continue;
      auto set = make_set(program_of(pass), bindings_of(pass, slot), reading(pass), uses[k]);
      if (!set) return failure{pass.label + ": " + set.error()};
      sets[std::size_t(slot)][k] = *set;
    }
  return true;
}

// The targets `pass` draws into, if it draws.
const vk::targets* renderer::impl::attachments(const scheduled_pass& pass) const {
  switch (pass.step) {
    case pass_step::gbuffer: return &out.gbuffers[std::size_t(pass.index)];
    case pass_step::ambient: return &out.lit;
    case pass_step::shadow: return &shadow_map;
    case pass_step::forward_light: return &lit_colour_only;
    case pass_step::light: return &out.light_buffers[std::size_t(pass.index)];
    case pass_step::compose:
    case pass_step::blend: return &out.composed;
    case pass_step::resolve: return plan.around_glass ? &glass_layers : &out.composed;
    // The exact reference's particles go into the lists, their overflow into the tail targets.
    case pass_step::particles: return plan.exact ? &tail : plan.around_glass ? &glass_layers : &out.composed;
    case pass_step::capture: return &tail;
    case pass_step::post: return &out.post.at(plan.post.passes[std::size_t(pass.index)].output);
    case pass_step::bake:
    case pass_step::bake_light:
    case pass_step::shadow_layer: break;
  }
  return nullptr;
}

// The images a transfer pass copies from and into.
std::vector<image_use> renderer::impl::copies(const scheduled_pass& pass) const {
  std::vector<image_use> u;
  if (pass.step == pass_step::shadow_layer)
    for (std::size_t t = 0; t < shadow_map.colors.size(); ++t) {
      u.push_back(copied(shadow_map.colors[t], false));
      u.push_back(copied(shadow_layers[t], true));
    }
  return u;
}

// One barrier: memory from `from` to `to`, and every image of `images` not in the layout it needs moved
// there after every access since its last move. The images are then in those layouts, accessed as they say.
void renderer::impl::settle(VkCommandBuffer cmd, access from, access to, const std::vector<image_use>& images) {
  moves.clear();
  for (const image_use& u : images) {
    image_state& st = layouts[u.handle];
    if (st.layout == u.layout) {
      st.since.stages |= u.at.stages;
      st.since.mask |= u.at.mask;
      continue;
    }
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = st.since.mask;
    b.dstAccessMask = u.at.mask;
    b.oldLayout = st.layout;
    b.newLayout = u.layout;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = u.handle;
    b.subresourceRange = {u.aspect, 0, VK_REMAINING_MIP_LEVELS, 0, VK_REMAINING_ARRAY_LAYERS};
    moves.push_back(b);
    from.stages |= st.since.stages;
    to.stages |= u.at.stages;
    st = {u.layout, u.aspect, u.at};
  }
  if (!from.stages && moves.empty()) return;
  VkMemoryBarrier m{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  m.srcAccessMask = from.mask;
  m.dstAccessMask = to.mask;
  // An image first used in this frame was last touched by the device's own submission: nothing to wait for.
  vkCmdPipelineBarrier(cmd, from.stages ? from.stages : VkPipelineStageFlags(VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT), to.stages, 0, from.stages ? 1 : 0, &m, 0,
                       nullptr, std::uint32_t(moves.size()), moves.data());
}

// Every image the frame left in another layout moved to SHADER_READ_ONLY_OPTIMAL (storage images stay in
// GENERAL), visible to shaders and copies: what the engine finds after the frame.
void renderer::impl::rest(VkCommandBuffer cmd) {
  resting.clear();
  const access read{VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT};
  for (const auto& [handle, st] : layouts)
    if (st.layout != VK_IMAGE_LAYOUT_GENERAL && st.layout != VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
      resting.push_back({handle, st.aspect, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, read});
  settle(cmd, {}, {}, resting);
}

// A barrier before `pass` from every earlier write of what it reads or writes, and from every read since
// of what it writes, with the moves of its images into their layouts; then `pass` is the last writer of
// what it writes and a reader of the rest.
void renderer::impl::barrier(VkCommandBuffer cmd, const scheduled_pass& pass, const std::vector<image_use>& images) {
  access from, to;
  const access r = reading(pass), w = writing(pass);
  auto writes = [&](const std::string& name) { return std::find(pass.writes.begin(), pass.writes.end(), name) != pass.writes.end(); };
  for (const std::string& name : pass.reads) {
    const state& s = states[name];
    if (!s.write.stages) continue;
    from.stages |= s.write.stages;
    from.mask |= s.write.mask;
    const access a = writes(name) ? w : r;
    to.stages |= a.stages;
    to.mask |= a.mask;
  }
  for (const std::string& name : pass.writes) {
    const state& s = states[name];
    if (s.write.stages) {
      from.stages |= s.write.stages;
      from.mask |= s.write.mask;
      to.stages |= w.stages;
      to.mask |= w.mask;
    }
    if (s.reads.stages) {
      from.stages |= s.reads.stages;
      to.stages |= w.stages;
    }
  }
  settle(cmd, from, to, images);
  for (const std::string& name : pass.reads)
    if (!writes(name)) {
      states[name].reads.stages |= r.stages;
      states[name].reads.mask |= r.mask;
    }
  for (const std::string& name : pass.writes) states[name] = {w, {}};
}

// The pictured light's shadow colour, copied out before the next light's shadow pass draws over it.
void renderer::impl::copy_shadow_picture(VkCommandBuffer cmd) {
  settle(cmd, {}, {}, {copied(shadow_map.colors[1], false)});
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {std::uint32_t(o.shadow_size), std::uint32_t(o.shadow_size), 1};
  vkCmdCopyImageToBuffer(cmd, shadow_map.colors[1].handle, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, out.shadow_picture.handle, 1, &copy);
  state& s = states["shadow map"];
  s.reads.stages |= VK_PIPELINE_STAGE_TRANSFER_BIT;
  memory_barrier(cmd, {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT}, {VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT});
}

// One pass of the schedule into `cmd`: its targets and clears, its pipeline and sets, its draws.
void renderer::impl::run(VkCommandBuffer cmd, const scheduled_pass& pass, VkDescriptorSet set, int slot,
                         const draw_geometry& draw) {
  // The still-camera variant binds what the compose pass binds: the pass's sets serve both.
  const program& p = pass.step == pass_step::compose && still_camera(previous) ? compose_still : program_of(pass);
  const VkDeviceSize zero = 0;
  const std::uint32_t i = std::uint32_t(std::max(pass.light, 0));
  if (pass.step == pass_step::capture) {
    // Empty lists: every head none, no node taken.
    VkClearColorValue empty{};
    empty.uint32[0] = 0xffffffffu;
    const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, out.kbuffer_heads.handle, VK_IMAGE_LAYOUT_GENERAL, &empty, 1, &all);
    const glm::uvec4 header(0u, 0u, out.kbuffer_capacity, 0u);
    vkCmdUpdateBuffer(cmd, out.kbuffer_nodes.handle, 0, sizeof header, &header);
    memory_barrier(cmd, {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT},
                   {VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT});
  }
  const vk::targets* into = attachments(pass);
  if (into) {
    dev.begin_rendering(cmd, *into, pass.clears, true);
    if (pass.area.z > 0) dev.set_area(cmd, pass.area);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.pipe.handle);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.pipe.layout, 0, 1, &set, 0, nullptr);
    // An engine's own geometry callback may draw with it unchanged: no faces culled.
    if (pass.step == pass_step::shadow) dev.set_cull_mode(cmd, VK_CULL_MODE_NONE);
  }
  if (zero_uv_binding >= 0 && draws_geometry(pass.step)) vkCmdBindVertexBuffers(cmd, std::uint32_t(zero_uv_binding), 1, &zero_uv.handle, &zero);
  switch (pass.step) {
    case pass_step::ambient:
      vkCmdBindVertexBuffers(cmd, light_index_binding, 1, &light_index.handle, &zero);
      draw(cmd, pass);
      break;
    case pass_step::forward_light: {
      // The engine draws instance 0: the light's index is bound where instance 0 reads it.
      const VkDeviceSize at = VkDeviceSize(i) * sizeof(std::uint32_t);
      vkCmdBindVertexBuffers(cmd, light_index_binding, 1, &light_index.handle, &at);
      draw(cmd, pass);
      break;
    }
    case pass_step::gbuffer:
    case pass_step::shadow:
    case pass_step::capture: draw(cmd, pass); break;
    case pass_step::light:
      vkCmdBindVertexBuffers(cmd, light_index_binding, 1, &light_index.handle, &zero);
      if (pass.kind == pass_kind::fullscreen) {
        vkCmdDraw(cmd, 3, 1, 0, i);
      } else {
        const bool sphere = volume_of(description.lights[i], o) == volume::sphere;
        vkCmdBindVertexBuffers(cmd, 0, 1, sphere ? &sphere_vertices.handle : &cone_vertices.handle, &zero);
        vkCmdBindIndexBuffer(cmd, sphere ? sphere_indices.handle : cone_indices.handle, 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, std::uint32_t(sphere ? sphere_count : cone_count), 1, 0, 0, i);
      }
      break;
    case pass_step::compose:
    case pass_step::blend:
    case pass_step::resolve:
    case pass_step::post: vkCmdDraw(cmd, 3, 1, 0, 0); break;
    case pass_step::particles:
      vkCmdBindVertexBuffers(cmd, 0, 1, &quads[std::size_t(slot)].handle, &zero);
      if (quad_counts[std::size_t(slot)]) vkCmdDraw(cmd, std::uint32_t(quad_counts[std::size_t(slot)]), 1, 0, 0);
      break;
    case pass_step::bake:
    case pass_step::bake_light:
    {
      const glm::ivec3 groups = bake_groups(smoke.atlas);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipe.handle);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipe.layout, 0, 1, &set, 0, nullptr);
      vkCmdDispatch(cmd, std::uint32_t(groups.x), std::uint32_t(groups.y), std::uint32_t(groups.z));
      break;
    }
    case pass_step::shadow_layer:
      for (std::size_t t = 0; t < shadow_map.colors.size(); ++t) {
        VkImageCopy copy{};
        copy.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, shadow_layer_of.at(pass.light), 1};
        copy.extent = {std::uint32_t(o.shadow_size), std::uint32_t(o.shadow_size), 1};
        vkCmdCopyImage(cmd, shadow_map.colors[t].handle, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, shadow_layers[t].handle,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
      }
      break;
  }
  if (into) dev.end_rendering(cmd);
  if (pass.step == pass_step::shadow && pass.light == pictured_light && out.shadow_picture.handle && frames_recorded == 0)
    copy_shadow_picture(cmd);  // once: the lights do not move
}

renderer::renderer(std::unique_ptr<impl> p) : p_(std::move(p)) {}
renderer::~renderer() = default;

result<std::unique_ptr<renderer>> renderer::create(device& dev, const scene& description, const render::options& o,
                                                   const pass_shaders& shaders, const vertex_input& vertices, int frames_in_flight) {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(dev.ctx().physical_device, &props);
  const VkPhysicalDeviceLimits& lim = props.limits;
  if (auto ok = fits_device(o, int(std::min({lim.maxImageDimension2D, lim.maxViewportDimensions[0], lim.maxViewportDimensions[1],
                                             lim.maxFramebufferWidth, lim.maxFramebufferHeight})));
      !ok)
    return failure{ok.error()};
  if (frames_in_flight < 1) return failure{"a renderer needs at least one frame in flight, not " + std::to_string(frames_in_flight)};
  auto p = std::make_unique<impl>(dev);
  p->description = description;
  p->o = o;
  p->plan = plan_of(description, o);
  p->light_data = light_blocks(description);
  p->smoke = particle_plan_of(description, p->plan, o, p->light_data);
  p->schedule = schedule_of(description, p->plan, o, p->light_data);
  p->vertices = vertices;
  p->slots = frames_in_flight;
  if (p->plan.on.has(effect::textures)) {
    bool coordinates = false;
    std::uint32_t last = light_index_binding;
    for (const VkVertexInputAttributeDescription& a : vertices.attributes) coordinates = coordinates || a.location == texture_coordinates_location;
    for (const VkVertexInputBindingDescription& b : vertices.bindings) last = std::max(last, b.binding);
    if (!coordinates) p->zero_uv_binding = int(last + 1);
  }
  const std::vector<format> final_formats{final_target_desc(o.float_targets).fmt};
  if (auto ok = p->make_pipelines(shaders, formats_of(gbuffer_targets(o.layout)), formats_of(light_targets(o)),
                                  formats_of(forward_targets(p->plan.forward_depth, o.float_targets)), final_formats);
      !ok)
    return failure{ok.error()};
  if (auto ok = p->make_fixed(); !ok) return failure{ok.error()};
  if (auto ok = p->make_sized(); !ok) return failure{ok.error()};
  for (object& ob : p->description.objects) ob.geometry = {};
  p->description.textures = {};  // uploaded: the frame reads none
  return std::unique_ptr<renderer>(new renderer(std::move(p)));
}

result<bool> renderer::resize(int width, int height) {
  render::options sized = p_->o;
  sized.width = width;
  sized.height = height;
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(p_->dev.ctx().physical_device, &props);
  if (auto ok = fits_device(sized, int(std::min(props.limits.maxImageDimension2D, props.limits.maxFramebufferWidth))); !ok) return ok;
  p_->destroy_sized();
  p_->o = sized;
  return p_->make_sized();
}

void renderer::record(VkCommandBuffer cmd, const camera& view, const draw_geometry& draw) {
  impl& r = *p_;
  const int slot = r.frames_recorded % r.slots;
  frame_block camera_block = sequence_frame(camera_frame(r.description, view, r.o), r.previous, r.sequence, r.plan, r.o);
  std::memcpy(r.camera_blocks[std::size_t(slot)].mapped, &camera_block, sizeof camera_block);
  set_camera_view(r.schedule, camera_block.view_proj);
  // Temporal interlacing draws into the other G-buffer and light buffer each frame; the last frame's become
  // the second layer, which the compose pass reads.
  if (r.plan.temporal && r.sequence > 0) r.swap_layers();
  r.previous = camera_block;
  ++r.sequence;
  if (r.smoke.on) {
    const std::vector<particle_vertex> q = particle_quads(r.description, view);
    r.quad_counts[std::size_t(slot)] = q.size();
    if (!q.empty()) std::memcpy(r.quads[std::size_t(slot)].mapped, q.data(), q.size() * sizeof(particle_vertex));
  }
  const std::uint32_t first = std::uint32_t(slot) * r.queries_per_frame;
  vkCmdResetQueryPool(cmd, r.queries, first, r.queries_per_frame);
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, r.queries, first);
  for (const impl::frame_clear& c : r.clears) {
    r.barrier(cmd, c.pass, c.images);
    if (!c.light_buffer) {
      const VkClearColorValue zero{};
      const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      vkCmdClearColorImage(cmd, r.out.volume_atlas.handle, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &all);
    } else {
      r.dev.begin_rendering(cmd, *c.light_buffer, c.zeros, true);
      r.dev.end_rendering(cmd);
    }
  }
  for (std::size_t k = 0; k < r.schedule.passes.size(); ++k) {
    const scheduled_pass& pass = r.schedule.passes[k];
    r.barrier(cmd, pass, r.uses[k]);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, r.queries, first + 2 + 2 * std::uint32_t(k));
    r.run(cmd, pass, r.sets[std::size_t(slot)][k], slot, draw);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, r.queries, first + 3 + 2 * std::uint32_t(k));
  }
  // What the host may read once the frame is done (the lists), and the image the engine
  // reads after the frame, which the next frame waits for before it writes it.
  memory_barrier(cmd, {VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT},
                 {VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT});
  r.rest(cmd);
  r.states[r.plan.post.passes.empty() ? "frame" : r.plan.post.output].reads.stages |= VK_PIPELINE_STAGE_ALL_COMMANDS_BIT;
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, r.queries, first + 1);
  r.last_slot = slot;
  ++r.frames_recorded;
}

frame_times renderer::times() const {
  const impl& r = *p_;
  if (r.last_slot < 0) return {};
  std::vector<std::uint64_t> ticks(r.queries_per_frame);
  vkGetQueryPoolResults(r.dev.ctx().device, r.queries, std::uint32_t(r.last_slot) * r.queries_per_frame, r.queries_per_frame,
                        ticks.size() * sizeof ticks[0], ticks.data(), sizeof ticks[0], VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
  auto ms = [&](std::uint64_t from, std::uint64_t to) { return double(to - from) * r.timestamp_ns * 1e-6; };
  std::vector<double> passes;
  for (std::size_t k = 0; k < r.schedule.passes.size(); ++k) passes.push_back(ms(ticks[2 + 2 * k], ticks[3 + 2 * k]));
  return times_of(r.schedule, passes, ms(ticks[0], ticks[1]));
}

const frame_schedule& renderer::schedule() const { return p_->schedule; }
const render::frame_plan& renderer::plan() const { return p_->plan; }
const render::options& renderer::options() const { return p_->o; }
const frame_targets& renderer::targets() const { return p_->out; }

result<std::unique_ptr<scene_geometry>> scene_geometry::create(device& dev, const scene& s) {
  std::unique_ptr<scene_geometry> g(new scene_geometry(dev));
  const scene_mesh m = flatten(s);
  g->hair_first_ = m.hair_first;
  g->index_count_ = m.indices.size();
  g->parts_ = m.parts;
  const VkBufferUsageFlags vertex_use = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
  result<buffer> made[] = {filled(dev, m.positions, vertex_use, "scene positions"), filled(dev, m.normals, vertex_use, "scene normals"),
                           filled(dev, m.materials, vertex_use, "scene materials"),
                           filled(dev, m.indices, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "scene indices"),
                           m.uvs.empty() ? result<buffer>(buffer{}) : filled(dev, m.uvs, vertex_use, "scene texture coordinates")};
  for (std::size_t k = 0; k < 5; ++k) {
    if (!made[k]) return failure{made[k].error()};
    g->buffers_[k] = *made[k];
  }
  return g;
}

vertex_input scene_geometry::input() const { return vertex_input::streams(buffers_[4].handle != VK_NULL_HANDLE); }

scene_geometry::~scene_geometry() {
  for (buffer& b : buffers_) dev_.destroy(b);
}

void scene_geometry::operator()(VkCommandBuffer cmd, const scheduled_pass& pass) const {
  const std::vector<index_run> runs = visible_runs(parts_, hair_first_, index_count_, pass);
  if (runs.empty()) return;
  const VkBuffer streams[] = {buffers_[0].handle, buffers_[1].handle, buffers_[2].handle};
  const VkDeviceSize offsets[] = {0, 0, 0};
  vkCmdBindVertexBuffers(cmd, 0, 3, streams, offsets);
  if (buffers_[4].handle) vkCmdBindVertexBuffers(cmd, texture_coordinates_binding, 1, &buffers_[4].handle, offsets);
  vkCmdBindIndexBuffer(cmd, buffers_[3].handle, 0, VK_INDEX_TYPE_UINT32);
  // A pass that may cull closed objects' back faces is drawn with a pipeline whose cull mode is dynamic
  // (pipeline_state::dynamic_cull): it is set for each run, and left as the pass's own after the last.
  const VkCullModeFlags own = pass.state.cull == culling::front ? VK_CULL_MODE_FRONT_BIT : VK_CULL_MODE_NONE;
  bool culling_back = false;
  for (const index_run& run : runs) {
    if (pass.state.cull_closed && run.cull_back != culling_back && dev_.set_cull_mode(cmd, run.cull_back ? VkCullModeFlags(VK_CULL_MODE_BACK_BIT) : own))
      culling_back = run.cull_back;
    vkCmdDrawIndexed(cmd, std::uint32_t(run.count), 1, std::uint32_t(run.first), 0, 0);
  }
  if (culling_back) dev_.set_cull_mode(cmd, own);
}

}  // namespace dstrans::vk

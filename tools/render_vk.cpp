// Implements render_vk.hpp. A frame is one submission of its passes, each between two timestamps and
// starting with a full memory barrier: the passes read what the one before wrote.
#include "render_vk.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <map>

#include <dstrans/particles.hpp>

#include <dstrans/frame/passes.hpp>

namespace dstrans::render {

namespace {

// Vulkan objects of one frame, released however the frame ends.
struct resources {
  vk::device& dev;
  std::vector<vk::buffer> buffers;
  std::vector<vk::pipeline> pipelines;
  std::vector<vk::targets> targets;
  std::vector<vk::image> images;
  VkSampler sampler = VK_NULL_HANDLE, linear_sampler = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;

  explicit resources(vk::device& d) : dev(d) {}
  ~resources() {
    const VkDevice device = dev.ctx().device;
    if (pool) vkDestroyDescriptorPool(device, pool, dev.ctx().allocator);
    if (sampler) vkDestroySampler(device, sampler, dev.ctx().allocator);
    if (linear_sampler) vkDestroySampler(device, linear_sampler, dev.ctx().allocator);
    for (auto& t : targets) dev.destroy(t);
    for (auto& i : images) dev.destroy(i);
    for (auto& p : pipelines) dev.destroy(p);
    for (auto& b : buffers) dev.destroy(b);
  }
  template <class T>
  result<VkBuffer> buffer(const std::vector<T>& data, VkBufferUsageFlags usage, const std::string& name) {
    auto b = dev.make_buffer(VkDeviceSize(std::max<std::size_t>(data.size(), 1) * sizeof(T)), usage, name);
    if (!b) return failure{b.error()};
    if (!data.empty()) std::memcpy(b->mapped, data.data(), data.size() * sizeof(T));
    buffers.push_back(*b);
    return b->handle;
  }
};

// What a descriptor set binds: buffers, and sampled or storage images, by binding number.
struct bindings {
  std::map<int, VkBuffer> buffers;
  std::map<int, VkImageView> images;
  std::map<int, VkSampler> samplers;  // for sampled images not read with resources::sampler (nearest)
};

// A descriptor set for `p` whose shaders are `stages`, filled from `b` by what the shaders declare.
result<VkDescriptorSet> make_set(resources& r, const vk::pipeline& p, const std::vector<const vk::shader*>& stages,
                                 const bindings& b) {
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = r.pool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &p.set_layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  if (vkAllocateDescriptorSets(r.dev.ctx().device, &ai, &set) != VK_SUCCESS)
    return failure{"descriptor pool exhausted"};
  std::vector<VkWriteDescriptorSet> writes;
  std::vector<VkDescriptorBufferInfo> buffer_infos;
  std::vector<VkDescriptorImageInfo> image_infos;
  buffer_infos.reserve(32);
  image_infos.reserve(32);
  std::map<int, bool> done;
  auto write = [&](int binding, VkDescriptorType type) -> result<bool> {
    if (done[binding]) return true;
    done[binding] = true;
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = set;
    w.dstBinding = std::uint32_t(binding);
    w.descriptorCount = 1;
    w.descriptorType = type;
    if (type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER || type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE) {
      const auto it = b.images.find(binding);
      if (it == b.images.end()) return failure{"nothing bound to image binding " + std::to_string(binding)};
      const bool sampled = type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
      const auto own = b.samplers.find(binding);
      image_infos.push_back({!sampled ? VK_NULL_HANDLE : own != b.samplers.end() ? own->second : r.sampler, it->second,
                             VK_IMAGE_LAYOUT_GENERAL});
      w.pImageInfo = &image_infos.back();
    } else {
      const auto it = b.buffers.find(binding);
      if (it == b.buffers.end()) return failure{"nothing bound to buffer binding " + std::to_string(binding)};
      buffer_infos.push_back({it->second, 0, VK_WHOLE_SIZE});
      w.pBufferInfo = &buffer_infos.back();
    }
    writes.push_back(w);
    return true;
  };
  for (const vk::shader* s : stages) {
    for (const auto& res : s->reflection.samplers)
      if (auto ok = write(res.binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER); !ok) return failure{ok.error()};
    for (const auto& res : s->reflection.uniform_buffers)
      if (auto ok = write(res.binding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER); !ok) return failure{ok.error()};
    for (const auto& res : s->reflection.storage_buffers)
      if (auto ok = write(res.binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER); !ok) return failure{ok.error()};
    for (const auto& res : s->reflection.storage_images)
      if (auto ok = write(res.binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE); !ok) return failure{ok.error()};
  }
  vkUpdateDescriptorSets(r.dev.ctx().device, std::uint32_t(writes.size()), writes.data(), 0, nullptr);
  return set;
}

void barrier(VkCommandBuffer cmd) {
  VkMemoryBarrier m{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  m.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  m.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &m, 0,
                       nullptr, 0, nullptr);
}

// Moves all of `img`'s layers from layout `from` to `to`, after everything before and before everything
// after: copies want TRANSFER_*_OPTIMAL, and dstrans keeps images in GENERAL between passes.
void relayout(VkCommandBuffer cmd, VkImage img, VkImageLayout from, VkImageLayout to) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = img;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, VK_REMAINING_ARRAY_LAYERS};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0,
                       nullptr, 1, &b);
}

struct compiled {
  const vk::shader* vertex;
  const vk::shader* fragment;
};

result<compiled> compile(vk::device& dev, const result<pass_sources>& p, const std::string& name) {
  if (!p) return failure{p.error()};
  auto v = dev.get_shader(p->vertex, spirv::stage::vertex, name + " (vertex)");
  if (!v) return failure{v.error()};
  auto f = dev.get_shader(p->fragment, spirv::stage::fragment, name + " (fragment)");
  if (!f) return failure{f.error()};
  return compiled{*v, *f};
}

VkVertexInputAttributeDescription attribute(std::uint32_t location, std::uint32_t binding, VkFormat f) {
  return {location, binding, f, 0};
}

}  // namespace

result<frame> render_vk(vk::device& dev, const scene& s, const options& o, const pass_shaders& shaders) {
  const vk::context& ctx = dev.ctx();
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(ctx.physical_device, &props);
  const VkPhysicalDeviceLimits& lim = props.limits;
  if (auto ok = fits_device(o, int(std::min({lim.maxImageDimension2D, lim.maxViewportDimensions[0], lim.maxViewportDimensions[1],
                                             lim.maxFramebufferWidth, lim.maxFramebufferHeight})));
      !ok)
    return failure{ok.error()};
  resources r(dev);
  const frame_plan plan = plan_of(s, o);
  const shadow_mode mode = plan.shadows;
  const bool any_shadows = mode != shadow_mode::off;

  // Deferred: one G-buffer and light buffer (interlaced), or one a peeled layer. Forward: one lit target,
  // and a view of its colour and depth alone for the light passes (it owns nothing).
  const bool forward = plan.forward, with_depth = plan.forward_depth, peeling = plan.peeling;
  const int layers = plan.layers;
  vk::targets lit, lit_colour_only;
  if (forward) {
    auto t = dev.make_targets(forward_targets(with_depth, o.float_targets), o.width, o.height, "forward", true);
    if (!t) return failure{t.error()};
    lit = *t;
    r.targets.push_back(lit);
    lit_colour_only = vk::targets{{lit.colors[0]}, {lit.formats[0]}, lit.depth, lit.width, lit.height};
  }
  std::vector<vk::targets> gbuffers, light_buffers;
  for (int k = 0; k < layers; ++k) {
    const std::string suffix = k ? " 2" : "";
    auto g = dev.make_targets(gbuffer_targets(o.layout), o.width, o.height, "gbuffer" + suffix, true);
    if (!g) return failure{g.error()};
    r.targets.push_back(*g);
    gbuffers.push_back(*g);
    auto l = dev.make_targets(light_targets(o.float_targets), o.width, o.height, "light buffer" + suffix, false);
    if (!l) return failure{l.error()};
    r.targets.push_back(*l);
    light_buffers.push_back(*l);
  }
  auto final_target =
      dev.make_targets({final_target_desc(o.float_targets)}, o.width, o.height, "final", false);
  if (!final_target) return failure{final_target.error()};
  r.targets.push_back(*final_target);
  vk::targets shadow_map;
  if (any_shadows) {
    auto sm = mode == shadow_mode::transparent
                  ? dev.make_targets(describe<thesis_shadow_map>(), o.shadow_size, o.shadow_size, "shadow map", true)
                  : dev.make_targets(describe<opaque_shadow_map>(), o.shadow_size, o.shadow_size, "shadow map", true);
    if (!sm) return failure{sm.error()};
    shadow_map = *sm;
    r.targets.push_back(shadow_map);
  }

  // Pipelines.
  const VkBufferUsageFlags vertex_use = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, index_use = VK_BUFFER_USAGE_INDEX_BUFFER_BIT;
  vk::pipeline_state scene_state;
  scene_state.bindings = {{0, sizeof(glm::vec3), VK_VERTEX_INPUT_RATE_VERTEX},
                          {1, sizeof(glm::vec3), VK_VERTEX_INPUT_RATE_VERTEX},
                          {2, sizeof(std::uint32_t), VK_VERTEX_INPUT_RATE_VERTEX}};
  scene_state.attributes = {attribute(0, 0, VK_FORMAT_R32G32B32_SFLOAT), attribute(1, 1, VK_FORMAT_R32G32B32_SFLOAT),
                            attribute(2, 2, VK_FORMAT_R32_UINT)};
  scene_state.depth_attachment = scene_state.depth_test = scene_state.depth_write = true;
  // The forward passes also read the light's index per instance, as the light volumes do.
  vk::pipeline_state forward_state = scene_state;
  forward_state.bindings.push_back({3, sizeof(std::uint32_t), VK_VERTEX_INPUT_RATE_INSTANCE});
  forward_state.attributes.push_back(attribute(3, 3, VK_FORMAT_R32_UINT));
  std::vector<compiled> gbuffer_shaders;
  std::vector<vk::pipeline> gbuffer_pipes;
  for (layer which : forward   ? std::vector<layer>{}
                     : peeling ? std::vector<layer>{layer::first, layer::second}
                               : std::vector<layer>{layer::interlaced}) {
    auto sh = compile(dev, gbuffer_pass(shaders, which, plan.on, o), "gbuffer pass");
    if (!sh) return failure{sh.error()};
    auto p = dev.make_graphics_pipeline(*sh->vertex, *sh->fragment, gbuffers[0].formats, "gbuffer pass", scene_state);
    if (!p) return failure{p.error()};
    r.pipelines.push_back(*p);
    gbuffer_shaders.push_back(*sh);
    gbuffer_pipes.push_back(*p);
  }

  result<compiled> shadow_shaders = failure{"unused"};
  vk::pipeline shadow_pipe;
  if (any_shadows) {
    shadow_shaders = compile(dev, shadow_pass(shaders, mode, plan.on), "shadow pass");
    if (!shadow_shaders) return failure{shadow_shaders.error()};
    auto p = dev.make_graphics_pipeline(*shadow_shaders->vertex, *shadow_shaders->fragment, shadow_map.formats,
                                        "shadow pass", scene_state);
    if (!p) return failure{p.error()};
    shadow_pipe = *p;
    r.pipelines.push_back(shadow_pipe);
  }

  // Light pipelines by [lookup][volume], for the lookups lights use; volumes are drawn with their back
  // faces, depth clamped (dstrans/frame/plan.hpp, volume).
  compiled light_shaders[3][2]{};
  vk::pipeline light_pipes[3][2]{};
  for (shadow_mode k : all_lookups)
    for (int vol = 0; vol < 2 && !forward && plan.uses(k); ++vol) {
      const std::string name = std::string("light pass") + lookup_label(k) + (vol ? " volume" : " fullscreen");
      auto sh = compile(dev, light_pass(shaders, k, vol == 1, o), name);
      if (!sh) return failure{sh.error()};
      light_shaders[int(k)][vol] = *sh;
      vk::pipeline_state st;
      st.additive = true;
      st.bindings.push_back({3, sizeof(std::uint32_t), VK_VERTEX_INPUT_RATE_INSTANCE});
      st.attributes.push_back(attribute(3, 3, VK_FORMAT_R32_UINT));
      if (vol) {
        st.bindings.push_back({0, sizeof(glm::vec3), VK_VERTEX_INPUT_RATE_VERTEX});
        st.attributes.push_back(attribute(0, 0, VK_FORMAT_R32G32B32_SFLOAT));
        st.cull = VK_CULL_MODE_FRONT_BIT;
        st.depth_clamp = true;
      }
      auto p = dev.make_graphics_pipeline(*sh->vertex, *sh->fragment, light_buffers[0].formats, name, st);
      if (!p) return failure{p.error()};
      light_pipes[int(k)][vol] = *p;
      r.pipelines.push_back(*p);
    }
  // Forward pipelines: ambient, light by [shadowed], and the blend (in place of the compose pass).
  compiled ambient_shaders{}, forward_light_shaders[3]{};
  vk::pipeline ambient_pipe, forward_light_pipes[3]{};
  if (forward) {
    auto a = compile(dev, forward_pass(shaders, forward_stage::ambient, with_depth, shadow_mode::off),
                     "forward ambient pass");
    if (!a) return failure{a.error()};
    ambient_shaders = *a;
    auto ap = dev.make_graphics_pipeline(*a->vertex, *a->fragment, lit.formats, "forward ambient pass", forward_state);
    if (!ap) return failure{ap.error()};
    ambient_pipe = *ap;
    r.pipelines.push_back(ambient_pipe);
    for (shadow_mode k : all_lookups) {
      if (!plan.uses(k)) continue;
      const std::string name = std::string("forward light pass") + lookup_label(k);
      auto sh = compile(dev, forward_pass(shaders, forward_stage::light, with_depth, k, o.physical_transmittance), name);
      if (!sh) return failure{sh.error()};
      forward_light_shaders[int(k)] = *sh;
      vk::pipeline_state st = forward_state;
      st.depth_write = false;
      st.depth_compare = VK_COMPARE_OP_LESS_OR_EQUAL;
      st.additive = true;
      auto p = dev.make_graphics_pipeline(*sh->vertex, *sh->fragment, lit_colour_only.formats, name, st);
      if (!p) return failure{p.error()};
      forward_light_pipes[int(k)] = *p;
      r.pipelines.push_back(*p);
    }
  }
  auto compose_shaders =
      forward ? compile(dev, forward_pass(shaders, forward_stage::blend, with_depth, shadow_mode::off),
                        "forward blend pass")
              : compile(dev, compose_pass(shaders, plan.on, o), "compose pass");
  if (!compose_shaders) return failure{compose_shaders.error()};
  auto compose_pipe = dev.make_graphics_pipeline(*compose_shaders->vertex, *compose_shaders->fragment,
                                                 final_target->formats, "compose pass");
  if (!compose_pipe) return failure{compose_pipe.error()};
  r.pipelines.push_back(*compose_pipe);

  // The k-buffer (many layers: hair) after the deferred frame; forward rendering draws no hair. The
  // capture pass adds overflow into the tail targets; the resolve lays the hair over the final image.
  const bool many = plan.on.has(effect::many_layers) && !forward;
  result<compiled> capture_shaders = failure{"unused"}, resolve_shaders = failure{"unused"};
  vk::pipeline capture_pipe, resolve_pipe;
  vk::targets tail;
  vk::image heads;
  vk::buffer nodes;
  const std::uint32_t capacity = kbuffer_capacity(o);
  if (many) {
    auto t = dev.make_targets(kbuffer_tail_targets(), o.width, o.height, "k-buffer tail", false);
    if (!t) return failure{t.error()};
    tail = *t;
    r.targets.push_back(tail);
    auto hi = dev.make_storage_image(VK_FORMAT_R32_UINT, o.width, o.height, "k-buffer heads");
    if (!hi) return failure{hi.error()};
    heads = *hi;
    auto nb = dev.make_buffer((VkDeviceSize(capacity) + 1u) * 16u, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "k-buffer nodes");
    if (!nb) return failure{nb.error()};
    nodes = *nb;
    r.buffers.push_back(nodes);
    capture_shaders = compile(dev, capture_pass(shaders, mode, o), "capture pass");
    if (!capture_shaders) return failure{capture_shaders.error()};
    vk::pipeline_state st = scene_state;
    st.additive = true;
    auto cp = dev.make_graphics_pipeline(*capture_shaders->vertex, *capture_shaders->fragment, tail.formats, "capture pass", st);
    if (!cp) return failure{cp.error()};
    capture_pipe = *cp;
    r.pipelines.push_back(capture_pipe);
    resolve_shaders = compile(dev, resolve_pass(shaders, mode, o), "resolve pass");
    if (!resolve_shaders) return failure{resolve_shaders.error()};
    vk::pipeline_state rs;
    rs.transmit = true;
    auto rp = dev.make_graphics_pipeline(*resolve_shaders->vertex, *resolve_shaders->fragment, final_target->formats,
                                         "resolve pass", rs);
    if (!rp) return failure{rp.error()};
    resolve_pipe = *rp;
    r.pipelines.push_back(resolve_pipe);
  }
  struct storage_image_guard {
    vk::device& dev;
    vk::image& image;
    ~storage_image_guard() { dev.destroy(image); }
  } heads_guard{dev, heads};

  // Light volumes (S2): particle systems over the deferred frame, lit from the atlas baked each frame (all
  // unshadowed lights in one dispatch a region, each shadowed spot light in its own right after its shadow
  // pass), or by the forward reference, which needs every shadow map at once: each is copied into a layer.
  const particle_plan smoke = particle_plan_of(s, plan, o);
  const bool particles = smoke.on, particle_reference = smoke.reference, baking = smoke.baking;
  const volume_atlas& atlas = smoke.atlas;
  const std::vector<volume_light>& shadowed_lights = smoke.shadowed_lights;
  const std::vector<volume_light>& unshadowed_lights = smoke.unshadowed_lights;
  const vk::shader* bake_shaders[2] = {};
  vk::pipeline bake_pipes[2]{}, particle_pipe;
  result<compiled> particle_shaders = failure{"unused"};
  vk::image atlas_image, shadow_layers[2];
  const glm::ivec3 atlas_size = glm::max(atlas.size, glm::ivec3(1));  // a forced effect with no system
  const std::size_t atlas_texels = std::size_t(atlas_size.x) * std::size_t(atlas_size.y) * std::size_t(atlas_size.z);
  if (particles) {
    for (const int shadowed : {0, 1}) {
      if (!baking || (shadowed ? shadowed_lights.empty() : unshadowed_lights.empty())) continue;
      const std::string name = shadowed ? "bake pass shadowed" : "bake pass";
      auto src = bake_pass(shaders, shadowed ? mode : shadow_mode::off, o);
      if (!src) return failure{src.error()};
      auto sh = dev.get_shader(*src, spirv::stage::compute, name);
      if (!sh) return failure{sh.error()};
      auto p = dev.make_compute_pipeline(**sh, name);
      if (!p) return failure{p.error()};
      r.pipelines.push_back(*p);
      bake_shaders[shadowed] = *sh;
      bake_pipes[shadowed] = *p;
    }
    particle_shaders = compile(dev, particle_pass(shaders, smoke.shadows, o), "particle pass");
    if (!particle_shaders) return failure{particle_shaders.error()};
    vk::pipeline_state st;
    st.transmit = true;  // colour premultiplied, and in alpha what the frame behind keeps
    st.bindings = {{0, sizeof(particle_vertex), VK_VERTEX_INPUT_RATE_VERTEX}};
    st.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, std::uint32_t(offsetof(particle_vertex, position))},
                     {1, 0, VK_FORMAT_R32_UINT, std::uint32_t(offsetof(particle_vertex, system))},
                     {2, 0, VK_FORMAT_R32G32B32A32_SFLOAT, std::uint32_t(offsetof(particle_vertex, corner))}};
    auto pp = dev.make_graphics_pipeline(*particle_shaders->vertex, *particle_shaders->fragment, final_target->formats,
                                         "particle pass", st);
    if (!pp) return failure{pp.error()};
    particle_pipe = *pp;
    r.pipelines.push_back(particle_pipe);
    if (baking) {
      auto img = dev.make_sampled_image(VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_VIEW_TYPE_3D, atlas_size.x, atlas_size.y,
                                        atlas_size.z, "volume atlas");
      if (!img) return failure{img.error()};
      atlas_image = *img;
      r.images.push_back(atlas_image);
    } else if (any_shadows && !shadowed_lights.empty()) {
      for (std::size_t t = 0; t < shadow_map.colors.size(); ++t) {
        auto img = dev.make_sampled_image(VkFormat(info(shadow_map.formats[t]).vk_format), VK_IMAGE_VIEW_TYPE_2D_ARRAY,
                                          o.shadow_size, o.shadow_size, int(shadowed_lights.size()),
                                          t ? "shadow layers colour" : "shadow layers depth");
        if (!img) return failure{img.error()};
        shadow_layers[t] = *img;
        r.images.push_back(shadow_layers[t]);
      }
    }
  }

  // The post-processing chain (post.hpp): a pipeline a pass, a target a name the passes write, and the
  // registry of names to images ("frame": the composed image).
  const post_plan& post = plan.post;
  std::vector<compiled> post_shaders;
  std::vector<vk::pipeline> post_pipes;
  std::map<std::string, vk::targets> post_targets;
  std::map<std::string, VkImageView> registry{{"frame", final_target->colors[0].view}};
  for (const post_pass& pass : post.passes) {
    auto sh = compile(dev, post_pass_sources(shaders, pass, o), "post " + pass.name);
    if (!sh) return failure{sh.error()};
    auto p = dev.make_graphics_pipeline(*sh->vertex, *sh->fragment, final_target->formats, "post " + pass.name);
    if (!p) return failure{p.error()};
    r.pipelines.push_back(*p);
    post_shaders.push_back(*sh);
    post_pipes.push_back(*p);
  }
  for (const std::string& name : post.targets) {
    auto t = dev.make_targets({final_target_desc(o.float_targets)}, o.width, o.height, "post " + name, false);
    if (!t) return failure{t.error()};
    r.targets.push_back(*t);
    post_targets[name] = *t;
    registry[name] = t->colors[0].view;
  }
  const vk::targets& shown = post.passes.empty() ? *final_target : post_targets.at(post.output);

  // Buffers.
  const std::vector<light_block> light_data = light_blocks(s);
  frame_block camera = camera_frame(s, o);
  camera.params.z = float(hair_shadow_light(plan));
  const scene_mesh m = flatten(s);
  std::vector<std::uint32_t> light_ids(s.lights.size());
  for (std::size_t i = 0; i < light_ids.size(); ++i) light_ids[i] = std::uint32_t(i);
  const mesh_data sphere = sphere_mesh(1), cone = cone_mesh(16);
  std::vector<result<VkBuffer>> made{
      r.buffer(m.positions, vertex_use, "scene positions"),
      r.buffer(m.normals, vertex_use, "scene normals"),
      r.buffer(m.materials, vertex_use, "scene materials"),
      r.buffer(m.indices, index_use, "scene indices"),
      r.buffer(light_ids, vertex_use, "light indices"),
      r.buffer(sphere.positions, vertex_use, "point light volume"),
      r.buffer(sphere.indices, index_use, "point light volume"),
      r.buffer(cone.positions, vertex_use, "spot light volume"),
      r.buffer(cone.indices, index_use, "spot light volume"),
      r.buffer(std::vector<frame_block>{camera}, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, "camera frame"),
      r.buffer(material_blocks(s), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "materials"),
      r.buffer(light_data, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "lights")};
  // The light volumes' buffers: the atlas's texels (the bake adds into them), each region's bake block,
  // the lights per dispatch; the particles' regions and quads.
  std::size_t particle_count = 0;
  for (const particle_system& ps : s.particles) particle_count += std::size_t(std::max(ps.count, 0));
  const std::vector<particle_vertex> quads = particles ? particle_quads(s, s.view) : std::vector<particle_vertex>{};
  std::vector<VkBuffer> region_blocks, shadowed_buffers;
  const std::size_t volume_first = made.size();
  const std::size_t texels_index = r.buffers.size();  // its mapped memory is cleared and read back
  if (particles) {
    made.push_back(r.buffer(std::vector<glm::vec4>(baking ? atlas_texels : 1),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, "volume texels"));
    made.push_back(r.buffer(unshadowed_lights, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "volume lights"));
    made.push_back(r.buffer(particle_regions(s, atlas), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "particle regions"));
    made.push_back(r.buffer(quads, vertex_use, "particle quads"));
    for (std::size_t k = 0; k < atlas.regions.size(); ++k)
      made.push_back(r.buffer(std::vector<volume_bake_block>{bake_block(atlas, k)}, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                              "volume region " + std::to_string(k)));
    for (const volume_light& l : shadowed_lights)
      made.push_back(r.buffer(std::vector<volume_light>{l}, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              "volume light " + std::to_string(int(l.cos_inner.y))));
  }
  const std::size_t post_first = made.size();
  for (const post_pass& pass : post.passes)
    made.push_back(r.buffer(std::vector<glm::vec4>{glm::vec4(pass.params[0], pass.params[1], pass.params[2], pass.params[3])},
                            VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, "post " + pass.name));
  for (const auto& b : made)
    if (!b) return failure{b.error()};
  VkBuffer volume_texels = VK_NULL_HANDLE, unshadowed_buffer = VK_NULL_HANDLE, regions_buffer = VK_NULL_HANDLE,
           quads_buffer = VK_NULL_HANDLE;
  if (particles) {
    volume_texels = *made[volume_first];
    unshadowed_buffer = *made[volume_first + 1];
    regions_buffer = *made[volume_first + 2];
    quads_buffer = *made[volume_first + 3];
    for (std::size_t k = 0; k < atlas.regions.size(); ++k) region_blocks.push_back(*made[volume_first + 4 + k]);
    for (std::size_t j = 0; j < shadowed_lights.size(); ++j)
      shadowed_buffers.push_back(*made[volume_first + 4 + atlas.regions.size() + j]);
  }
  const VkBuffer positions = *made[0], normals = *made[1], materials = *made[2], indices = *made[3],
                 light_index = *made[4], sphere_vertices = *made[5], sphere_indices = *made[6],
                 cone_vertices = *made[7], cone_indices = *made[8], frame_ubo = *made[9], material_ssbo = *made[10],
                 light_ssbo = *made[11];

  VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  vkCreateSampler(ctx.device, &sci, ctx.allocator, &r.sampler);
  sci.magFilter = sci.minFilter = VK_FILTER_LINEAR;  // the volume atlas is read trilinearly
  vkCreateSampler(ctx.device, &sci, ctx.allocator, &r.linear_sampler);
  const std::uint32_t sets =
      std::uint32_t(7 + 2 * s.lights.size() + atlas.regions.size() * (1 + shadowed_lights.size()) + post.passes.size());
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 2 * sets},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 4 * sets},
                                        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 8 * sets},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2}};
  VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pci.maxSets = sets;
  pci.poolSizeCount = 4;
  pci.pPoolSizes = sizes;
  vkCreateDescriptorPool(ctx.device, &pci, ctx.allocator, &r.pool);

  // What every pass binds (the frame's blocks and the shadow map); what each layer's passes bind on top
  // (its G-buffer at the G-buffer bindings); the compose pass sees both layers, the blend the lit target.
  bindings base;
  base.buffers = {{binding(slot::frame), frame_ubo}, {binding(slot::materials), material_ssbo}, {binding(slot::lights), light_ssbo}};
  if (any_shadows)
    for (std::size_t t = 0; t < shadow_map.colors.size(); ++t)
      base.images[binding(slot::shadow_map) + int(t)] = shadow_map.colors[t].view;
  // A G-buffer's images at `first` and up (the compact layout's depth attachment at its depth slot).
  auto bind_gbuffer = [&](bindings& b, int first, const vk::targets& g) {
    for (std::size_t t = 0; t < g.colors.size(); ++t) b.images[first + int(t)] = g.colors[t].view;
    if (o.layout == gbuffer_layout::compact) b.images[first + gbuffer_depth_slot] = g.depth.view;
  };
  std::vector<bindings> per_layer(static_cast<std::size_t>(layers), base);
  for (int k = 0; k < layers; ++k) {
    bindings& b = per_layer[std::size_t(k)];
    bind_gbuffer(b, binding(slot::gbuffer), gbuffers[std::size_t(k)]);
    b.images[binding(slot::light)] = light_buffers[std::size_t(k)].colors[0].view;
    b.images[binding(slot::peel_depth)] = o.layout == gbuffer_layout::compact ? gbuffers[0].depth.view : gbuffers[0].colors[3].view;
  }
  bindings common = forward ? base : per_layer[0];
  bindings layers_set = common;  // the k-buffer passes: the first G-buffer, the lists, the tail
  if (many) {
    layers_set.images[binding(slot::kbuffer_heads)] = heads.view;
    layers_set.buffers[binding(slot::kbuffer_nodes)] = nodes.handle;
    for (int t = 0; t < 2; ++t) layers_set.images[binding(slot::kbuffer_tail) + t] = tail.colors[std::size_t(t)].view;
  }
  if (forward)
    for (std::size_t t = 0; t < lit.colors.size(); ++t) common.images[binding(slot::forward_lit) + int(t)] = lit.colors[t].view;
  if (peeling) {
    bind_gbuffer(common, binding(slot::gbuffer2), gbuffers[1]);
    common.images[binding(slot::light2)] = light_buffers[1].colors[0].view;
  }

  // One bake dispatch a region with the lights in `lights`, reading the camera's frame and the shadow map.
  auto bake = [&](int shadowed, VkBuffer lights) -> result<std::function<void(VkCommandBuffer)>> {
    std::vector<VkDescriptorSet> region_sets;
    for (std::size_t k = 0; k < atlas.regions.size(); ++k) {
      bindings b = base;
      b.buffers[binding(slot::volume_lights)] = lights;
      b.buffers[binding(slot::volume_texels)] = volume_texels;
      b.buffers[binding(slot::volume_region)] = region_blocks[k];
      auto set = make_set(r, bake_pipes[shadowed], {bake_shaders[shadowed]}, b);
      if (!set) return failure{set.error()};
      region_sets.push_back(*set);
    }
    return std::function<void(VkCommandBuffer)>([&, shadowed, region_sets](VkCommandBuffer cmd) {
      barrier(cmd);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, bake_pipes[shadowed].handle);
      for (std::size_t k = 0; k < atlas.regions.size(); ++k) {
        const glm::ivec4 d = atlas.regions[k].dims;
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, bake_pipes[shadowed].layout, 0, 1, &region_sets[k], 0, nullptr);
        vkCmdDispatch(cmd, std::uint32_t(d.x + 3) / 4, std::uint32_t(d.y + 3) / 4, std::uint32_t(d.z + 3) / 4);
      }
    });
  };
  bindings particle_set = common;
  if (particles) {
    particle_set.buffers[binding(slot::particle_regions)] = regions_buffer;
    if (baking) {
      particle_set.images[binding(slot::volume_atlas)] = atlas_image.view;
      particle_set.samplers[binding(slot::volume_atlas)] = r.linear_sampler;
    }
    for (int t = 0; t < 2; ++t)
      if (shadow_layers[t].view) particle_set.images[binding(slot::shadow_layers) + t] = shadow_layers[t].view;
  }

  frame out;
  std::vector<texel> shadow_picture;
  // Where the pictured shadow map's colour (RGBA8) is copied within the frame.
  vk::buffer shadow_picture_buffer;
  if (mode == shadow_mode::transparent &&
      std::any_of(plan.lookups.begin(), plan.lookups.end(), [](shadow_mode lookup) { return lookup != shadow_mode::off; })) {
    auto b = dev.make_buffer(VkDeviceSize(o.shadow_size) * VkDeviceSize(o.shadow_size) * 4u,
                             VK_BUFFER_USAGE_TRANSFER_DST_BIT, "shadow picture");
    if (!b) return failure{b.error()};
    shadow_picture_buffer = *b;
    r.buffers.push_back(*b);
  }
  std::map<std::string, double> current;  // this frame's pass times
  std::vector<std::map<std::string, double>> frames;
  // The passes of the frame being recorded, by name, in the order of their timestamps.
  std::vector<std::string> recorded;
  auto timed = [&](const std::string& pass, const std::function<void(VkCommandBuffer)>& record) {
    recorded.push_back(pass);
    dev.record_pass(record);
  };
  std::vector<double> totals;  // each frame's one submission
  // Each shadowed light's view, made once for all frames.
  std::vector<VkBuffer> light_ubos(s.lights.size(), VK_NULL_HANDLE);
  for (std::size_t i = 0; i < s.lights.size(); ++i)
    if (plan.lookups[i] != shadow_mode::off) {
      auto ubo = r.buffer(std::vector<frame_block>{light_frame(s, light_data[i], o)}, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                          "light frame");
      if (!ubo) return failure{ubo.error()};
      light_ubos[i] = *ubo;
    }
  const VkDeviceSize zero = 0;

  // The scene's triangles from `first` to `last` (hair comes last: scene_mesh::hair_first).
  auto draw_scene = [&](VkCommandBuffer cmd, std::size_t first, std::size_t last) {
    const VkBuffer vb[] = {positions, normals, materials};
    const VkDeviceSize offsets[] = {0, 0, 0};
    vkCmdBindVertexBuffers(cmd, 0, 3, vb, offsets);
    vkCmdBindIndexBuffer(cmd, indices, 0, VK_INDEX_TYPE_UINT32);
    if (last > first) vkCmdDrawIndexed(cmd, std::uint32_t(last - first), 1, std::uint32_t(first), 0, 0);
  };
  // At most: two G-buffers, the ambient pass, two bakes, the atlas, the compose, capture, resolve and
  // particles; per light a shadow, a bake, a copy, a forward light and two light passes; the post chain.
  const std::size_t max_passes = 16 + 6 * s.lights.size() + post.passes.size();
  for (int n = 0; n < std::max(o.frames, 1); ++n) {
    current.clear();
    recorded.clear();
    vkResetDescriptorPool(ctx.device, r.pool, 0);  // the last frame's submission has completed
    const VkCommandBuffer frame_cmd = dev.begin_passes(max_passes);
    // G-buffers: empty pixels are opaque black at the far plane. The second peeled layer reads the first's depth.
    for (int k = 0; k < layers; ++k) {
      const vk::pipeline& p = gbuffer_pipes[std::size_t(k)];
      auto set = make_set(r, p, {gbuffer_shaders[std::size_t(k)].vertex, gbuffer_shaders[std::size_t(k)].fragment},
                          per_layer[0]);
      if (!set) return failure{set.error()};
      timed("gbuffer", [&](VkCommandBuffer cmd) {
        barrier(cmd);
        dev.begin_rendering(cmd, gbuffers[std::size_t(k)], gbuffer_clears(o.layout));
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.handle);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.layout, 0, 1, &*set, 0, nullptr);
        draw_scene(cmd, 0, m.hair_first);
        dev.end_rendering(cmd);
      });
    }

    if (forward) {
      auto set = make_set(r, ambient_pipe, {ambient_shaders.vertex, ambient_shaders.fragment}, base);
      if (!set) return failure{set.error()};
      timed("ambient", [&](VkCommandBuffer cmd) {
        barrier(cmd);
        std::vector<glm::vec4> clear{glm::vec4(0, 0, 0, 1), glm::vec4(0.0f)};
        if (with_depth) clear.push_back(glm::vec4(1.0f));
        dev.begin_rendering(cmd, lit, clear);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, ambient_pipe.handle);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, ambient_pipe.layout, 0, 1, &*set, 0, nullptr);
        vkCmdBindVertexBuffers(cmd, 3, 1, &light_index, &zero);
        draw_scene(cmd, 0, m.hair_first);
        dev.end_rendering(cmd);
      });
    }
    barrier(frame_cmd);
    for (const vk::targets& lb : light_buffers) {
      dev.begin_rendering(frame_cmd, lb, {glm::vec4(0.0f)});
      dev.end_rendering(frame_cmd);
    }
    if (baking) {
      // Written before the submission, which reads it first; the last frame's has completed.
      std::memset(r.buffers[texels_index].mapped, 0, atlas_texels * sizeof(glm::vec4));
      if (bake_pipes[0].handle) {
        auto rec = bake(0, unshadowed_buffer);
        if (!rec) return failure{rec.error()};
        timed("bake", *rec);
      }
    }
    std::size_t shadow_layer = 0;
    for (std::size_t i = 0; i < s.lights.size(); ++i) {
      const light& l = s.lights[i];
      const shadow_mode lookup = plan.lookups[i];
      const bool shadowed = lookup != shadow_mode::off;
      if (shadowed) {
        bindings seen_from_light = common;
        seen_from_light.buffers[binding(slot::frame)] = light_ubos[i];
        auto set = make_set(r, shadow_pipe, {shadow_shaders->vertex, shadow_shaders->fragment}, seen_from_light);
        if (!set) return failure{set.error()};
        timed("shadow", [&](VkCommandBuffer cmd) {
          barrier(cmd);
          dev.begin_rendering(cmd, shadow_map, std::vector<glm::vec4>(shadow_map.colors.size(), glm::vec4(1.0f)));
          vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shadow_pipe.handle);
          vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shadow_pipe.layout, 0, 1, &*set, 0, nullptr);
          draw_scene(cmd, 0, m.indices.size());
          dev.end_rendering(cmd);
        });
        // The first shadowed light's map is the one pictured (Figure 4.4 of the thesis shows one): its colour
        // is copied out before the next light's shadow pass draws over it.
        if (mode == shadow_mode::transparent && shadow_layer == 0 && n == 0) {  // once: the lights do not move
          barrier(frame_cmd);
          relayout(frame_cmd, shadow_map.colors[1].handle, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
          VkBufferImageCopy copy{};
          copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
          copy.imageExtent = {std::uint32_t(o.shadow_size), std::uint32_t(o.shadow_size), 1};
          vkCmdCopyImageToBuffer(frame_cmd, shadow_map.colors[1].handle, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                 shadow_picture_buffer.handle, 1, &copy);
          relayout(frame_cmd, shadow_map.colors[1].handle, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
        }
        if (baking) {
          auto rec = bake(1, shadowed_buffers[shadow_layer]);
          if (!rec) return failure{rec.error()};
          timed("bake", *rec);
        }
        if (particle_reference)
          timed("particles", [&](VkCommandBuffer cmd) {
            barrier(cmd);
            for (std::size_t t = 0; t < shadow_map.colors.size(); ++t) {
              const VkImage from = shadow_map.colors[t].handle, to = shadow_layers[t].handle;
              relayout(cmd, from, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
              relayout(cmd, to, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
              VkImageCopy copy{};
              copy.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
              copy.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, std::uint32_t(shadow_layer), 1};
              copy.extent = {std::uint32_t(o.shadow_size), std::uint32_t(o.shadow_size), 1};
              vkCmdCopyImage(cmd, from, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, to, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
              relayout(cmd, from, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
              relayout(cmd, to, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
            }
          });
        ++shadow_layer;
      }
      if (forward) {
        const vk::pipeline& p = forward_light_pipes[int(lookup)];
        const compiled& sh = forward_light_shaders[int(lookup)];
        auto set = make_set(r, p, {sh.vertex, sh.fragment}, base);
        if (!set) return failure{set.error()};
        timed("light", [&](VkCommandBuffer cmd) {
          barrier(cmd);
          dev.begin_rendering(cmd, lit_colour_only, {});
          vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.handle);
          vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.layout, 0, 1, &*set, 0, nullptr);
          const VkBuffer vb[] = {positions, normals, materials, light_index};
          const VkDeviceSize offsets[] = {0, 0, 0, 0};
          vkCmdBindVertexBuffers(cmd, 0, 4, vb, offsets);
          vkCmdBindIndexBuffer(cmd, indices, 0, VK_INDEX_TYPE_UINT32);
          vkCmdDrawIndexed(cmd, std::uint32_t(m.hair_first), 1, 0, 0, std::uint32_t(i));
          dev.end_rendering(cmd);
        });
        continue;
      }
      const volume v = volume_of(l, o);
      const int vol = v == volume::fullscreen ? 0 : 1;
      const vk::pipeline& p = light_pipes[int(lookup)][vol];
      const compiled& sh = light_shaders[int(lookup)][vol];
      for (int k = 0; k < layers; ++k) {
        auto set = make_set(r, p, {sh.vertex, sh.fragment}, per_layer[std::size_t(k)]);
        if (!set) return failure{set.error()};
        timed("light", [&](VkCommandBuffer cmd) {
          barrier(cmd);
          dev.begin_rendering(cmd, light_buffers[std::size_t(k)], {});
          vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.handle);
          vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.layout, 0, 1, &*set, 0, nullptr);
          vkCmdBindVertexBuffers(cmd, 3, 1, &light_index, &zero);
          if (v == volume::fullscreen) {
            vkCmdDraw(cmd, 3, 1, 0, std::uint32_t(i));
          } else {
            const bool is_sphere = v == volume::sphere;
            vkCmdBindVertexBuffers(cmd, 0, 1, is_sphere ? &sphere_vertices : &cone_vertices, &zero);
            vkCmdBindIndexBuffer(cmd, is_sphere ? sphere_indices : cone_indices, 0, VK_INDEX_TYPE_UINT32);
            vkCmdDrawIndexed(cmd, std::uint32_t(is_sphere ? sphere.indices.size() : cone.indices.size()), 1, 0, 0,
                             std::uint32_t(i));
          }
          dev.end_rendering(cmd);
        });
      }
    }

    if (baking)
      timed("bake", [&](VkCommandBuffer cmd) {
        relayout(cmd, atlas_image.handle, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {std::uint32_t(atlas_size.x), std::uint32_t(atlas_size.y), std::uint32_t(atlas_size.z)};
        vkCmdCopyBufferToImage(cmd, volume_texels, atlas_image.handle, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        relayout(cmd, atlas_image.handle, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
      });

    auto compose_set = make_set(r, *compose_pipe, {compose_shaders->vertex, compose_shaders->fragment}, common);
    if (!compose_set) return failure{compose_set.error()};
    timed(forward ? "blend" : "compose", [&](VkCommandBuffer cmd) {
      barrier(cmd);
      dev.begin_rendering(cmd, *final_target, {glm::vec4(0.0f)});
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, compose_pipe->handle);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, compose_pipe->layout, 0, 1, &*compose_set, 0,
                              nullptr);
      vkCmdDraw(cmd, 3, 1, 0, 0);
      dev.end_rendering(cmd);
    });
    if (many) {
      const glm::uvec4 header(0u, 0u, capacity, 0u);
      std::memcpy(nodes.mapped, &header, sizeof header);  // the last submission has completed
      auto capture_set = make_set(r, capture_pipe, {capture_shaders->vertex, capture_shaders->fragment}, layers_set);
      if (!capture_set) return failure{capture_set.error()};
      timed("capture", [&](VkCommandBuffer cmd) {
        barrier(cmd);
        VkClearColorValue empty{};
        empty.uint32[0] = 0xffffffffu;
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd, heads.handle, VK_IMAGE_LAYOUT_GENERAL, &empty, 1, &all);
        barrier(cmd);
        dev.begin_rendering(cmd, tail, {glm::vec4(0.0f), glm::vec4(0.0f)});
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, capture_pipe.handle);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, capture_pipe.layout, 0, 1, &*capture_set, 0, nullptr);
        draw_scene(cmd, m.hair_first, m.indices.size());
        dev.end_rendering(cmd);
      });
      auto resolve_set = make_set(r, resolve_pipe, {resolve_shaders->vertex, resolve_shaders->fragment}, layers_set);
      if (!resolve_set) return failure{resolve_set.error()};
      timed("resolve", [&](VkCommandBuffer cmd) {
        barrier(cmd);
        dev.begin_rendering(cmd, *final_target, {});
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, resolve_pipe.handle);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, resolve_pipe.layout, 0, 1, &*resolve_set, 0, nullptr);
        vkCmdDraw(cmd, 3, 1, 0, 0);
        dev.end_rendering(cmd);
      });
    }
    if (particles) {
      auto set = make_set(r, particle_pipe, {particle_shaders->vertex, particle_shaders->fragment}, particle_set);
      if (!set) return failure{set.error()};
      timed("particles", [&](VkCommandBuffer cmd) {
        barrier(cmd);
        dev.begin_rendering(cmd, *final_target, {});
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, particle_pipe.handle);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, particle_pipe.layout, 0, 1, &*set, 0, nullptr);
        vkCmdBindVertexBuffers(cmd, 0, 1, &quads_buffer, &zero);
        if (!quads.empty()) vkCmdDraw(cmd, std::uint32_t(quads.size()), 1, 0, 0);
        dev.end_rendering(cmd);
      });
    }
    for (std::size_t k = 0; k < post.passes.size(); ++k) {
      const post_pass& pass = post.passes[k];
      bindings b = common;
      b.buffers[binding(slot::post_params)] = *made[post_first + k];
      int input = binding(slot::post_input);
      for (const std::string& in : pass.inputs)
        if (in != "gbuffer") b.images[input++] = registry.at(in);
      auto set = make_set(r, post_pipes[k], {post_shaders[k].vertex, post_shaders[k].fragment}, b);
      if (!set) return failure{set.error()};
      timed("post " + pass.effect, [&](VkCommandBuffer cmd) {
        barrier(cmd);
        dev.begin_rendering(cmd, post_targets.at(pass.output), {});
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, post_pipes[k].handle);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, post_pipes[k].layout, 0, 1, &*set, 0, nullptr);
        vkCmdDraw(cmd, 3, 1, 0, 0);
        dev.end_rendering(cmd);
      });
    }
    auto ms = dev.submit_passes();
    if (!ms) return failure{ms.error()};
    for (std::size_t k = 0; k < recorded.size(); ++k) current[recorded[k]] += (*ms)[k];
    totals.push_back(ms->back());
    frames.push_back(current);
  }
  summarize(frames, totals, out);
  out.schedule = recorded;
  if (shadow_picture_buffer.mapped) {
    shadow_picture.resize(std::size_t(o.shadow_size) * std::size_t(o.shadow_size));
    const auto* bytes = static_cast<const std::uint8_t*>(shadow_picture_buffer.mapped);
    for (std::size_t i = 0; i < shadow_picture.size(); ++i) std::memcpy(shadow_picture[i].data(), bytes + 4 * i, 4);
  }
  if (baking) {
    const auto* t = static_cast<const glm::vec4*>(r.buffers[texels_index].mapped);
    out.volume_texels.assign(t, t + atlas_texels);
  }

  const int w = o.width, h = o.height;
  auto picture = [&](const vk::targets& t, int index, format f, int pw, int ph, view_as how) -> result<image> {
    auto texels = dev.read_texels(t, index);
    if (!texels) return failure{texels.error()};
    return to_image(*texels, f, pw, ph, how, s.view.near_plane, s.view.far_plane);
  };
  if (forward)
    for (std::size_t t = 0; t < lit.colors.size(); ++t) {
      auto texels = dev.read_texels(lit, int(t));
      if (!texels) return failure{texels.error()};
      out.lit.push_back(*texels);
    }
  if (!forward) {
    for (std::size_t t = 0; t < gbuffers[0].colors.size(); ++t) {
      auto texels = dev.read_texels(gbuffers[0], int(t));
      if (!texels) return failure{texels.error()};
      out.gbuffer.push_back(*texels);
    }
    auto light_texels = dev.read_texels(light_buffers[0], 0);
    if (!light_texels) return failure{light_texels.error()};
    out.light_buffer = *light_texels;
  }
  auto final_texels = dev.read_texels(shown, 0);
  if (!final_texels) return failure{final_texels.error()};
  out.final_texels = *final_texels;
  if (many) {
    auto head_texels = dev.read_words(heads, o.width, o.height);
    if (!head_texels) return failure{head_texels.error()};
    out.kbuffer_heads = *head_texels;
    const auto* pool = static_cast<const glm::uvec4*>(nodes.mapped);
    out.kbuffer_overflow = pool[0].y;
    out.kbuffer_nodes.assign(pool + 1, pool + 1 + std::min(pool[0].x, capacity));
  }
  out.final_image = to_image(out.final_texels, final_target_desc(o.float_targets).fmt, w, h, view_as::rgb);
  const format light_format = light_targets(o.float_targets)[0].fmt;
  std::vector<std::tuple<std::string, const vk::targets*, int, format, view_as>> wanted;
  if (forward) {
    wanted = {{"colour", &lit, 0, lit.formats[0], view_as::rgb}, {"normals", &lit, 1, format::rgb10a2, view_as::rgb}};
    if (with_depth) wanted.push_back({"depth", &lit, 2, format::r32f, view_as::depth});
  }
  for (int k = 0; k < layers; ++k) {
    const std::string suffix = k ? "_2" : "";
    const vk::targets *gb = &gbuffers[std::size_t(k)], *lb = &light_buffers[std::size_t(k)];
    wanted.push_back({"diffuse" + suffix, gb, 0, format::rgba8, view_as::rgb});
    if (o.layout == gbuffer_layout::thesis)  // the compact layout's normals are octahedral, its depth an attachment
      wanted.insert(wanted.end(), {{"normals" + suffix, gb, 1, format::rgb10a2, view_as::rgb},
                                   {"depth" + suffix, gb, 3, format::r32f, view_as::depth}});
    wanted.insert(wanted.end(), {{"light" + suffix, lb, 0, light_format, view_as::rgb},
                                 {"specular" + suffix, lb, 0, light_format, view_as::alpha}});
  }
  if (!post.passes.empty()) {
    wanted.push_back({"composed", &*final_target, 0, final_target_desc(o.float_targets).fmt, view_as::rgb});
    for (const std::string& effect : post.effects)
      wanted.push_back({"post_" + effect, &post_targets.at(effect), 0, final_target_desc(o.float_targets).fmt, view_as::rgb});
  }
  for (const auto& [name, t, index, f, how] : wanted) {
    auto img = picture(*t, index, f, w, h, how);
    if (!img) return failure{img.error()};
    out.buffers.push_back({name, *img});
  }
  if (!shadow_picture.empty())
    out.buffers.push_back(
        {"shadow_colour", to_image(shadow_picture, format::rgba8, o.shadow_size, o.shadow_size, view_as::rgb)});
  return out;
}

}  // namespace dstrans::render

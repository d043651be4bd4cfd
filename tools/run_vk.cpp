// Implements run_vk.hpp.
#include "run_vk.hpp"

#include <algorithm>
#include <memory>
#include <cstring>
#include <tuple>

#include <dstrans/frame/passes.hpp>
#include <dstrans/fullscreen.hpp>
#include <dstrans_vk_frame.hpp>

#include "same_objects.hpp"

namespace dstrans::render {

namespace {

// What the frame's targets hold, as frame_output.hpp keeps it.
result<bool> read_back(vk::device& dev, const vk::renderer& r, const scene& s, frame& out) {
  const options& o = r.options();
  const vk::frame_targets& t = r.targets();
  const frame_plan& plan = r.plan();
  const int w = o.width, h = o.height;
  auto texels = [&](const vk::targets& from, int index, std::vector<texel>& into) -> result<bool> {
    auto got = dev.read_texels(from, index, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    if (!got) return failure{got.error()};
    into = *got;
    return true;
  };
  if (plan.forward) {
    out.lit.resize(t.lit.colors.size());
    for (std::size_t k = 0; k < t.lit.colors.size(); ++k)
      if (auto ok = texels(t.lit, int(k), out.lit[k]); !ok) return ok;
  } else {
    out.gbuffer.resize(t.gbuffers[0].colors.size());
    for (std::size_t k = 0; k < t.gbuffers[0].colors.size(); ++k)
      if (auto ok = texels(t.gbuffers[0], int(k), out.gbuffer[k]); !ok) return ok;
    if (auto ok = texels(t.light_buffers[0], 0, out.light_buffer); !ok) return ok;
  }
  if (auto ok = texels(*t.output, 0, out.final_texels); !ok) return ok;
  if (t.kbuffer_heads.view) {
    auto heads = dev.read_words(t.kbuffer_heads, w, h);
    if (!heads) return failure{heads.error()};
    out.kbuffer_heads = *heads;
    const auto* pool = static_cast<const glm::uvec4*>(t.kbuffer_nodes.mapped);
    out.kbuffer_overflow = pool[0].y;
    out.kbuffer_nodes.assign(pool + 1, pool + 1 + std::min(pool[0].x, t.kbuffer_capacity));
  }
  if (t.volume_atlas.view) {
    auto atlas = dev.read_volume(t.volume_atlas, 4, t.volume_atlas_size, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    if (!atlas) return failure{atlas.error()};
    out.volume_atlas = *atlas;
  }
  const format final_format = final_target_desc(o.float_targets).fmt;
  out.final_image = to_image(out.final_texels, final_format, w, h, view_as::rgb);
  const format light_format = light_targets(o)[0].fmt;
  std::vector<std::tuple<std::string, const vk::targets*, int, format, view_as>> wanted;
  if (plan.forward) {
    wanted = {{"colour", &t.lit, 0, t.lit.formats[0], view_as::rgb}, {"normals", &t.lit, 1, format::rgb10a2, view_as::rgb}};
    if (plan.forward_depth) wanted.push_back({"depth", &t.lit, 2, format::r32f, view_as::depth});
  }
  for (std::size_t k = 0; k < t.gbuffers.size(); ++k) {
    const std::string suffix = k ? "_2" : "";
    const vk::targets *gb = &t.gbuffers[k], *lb = &t.light_buffers[k];
    wanted.push_back({"diffuse" + suffix, gb, 0, format::rgba8, view_as::rgb});
    if (o.layout == gbuffer_layout::thesis)  // the compact layout's normals are octahedral, its depth an attachment
      wanted.insert(wanted.end(), {{"normals" + suffix, gb, 1, format::rgb10a2, view_as::rgb}, {"depth" + suffix, gb, 3, format::r32f, view_as::depth}});
    wanted.insert(wanted.end(), {{"light" + suffix, lb, 0, light_format, view_as::rgb}, {"specular" + suffix, lb, o.rgb_specular ? 1 : 0, light_format, o.rgb_specular ? view_as::rgb : view_as::alpha}});
  }
  if (!plan.post.passes.empty()) {
    wanted.push_back({"composed", &t.composed, 0, final_format, view_as::rgb});
    for (const std::string& effect : plan.post.effects) wanted.push_back({"post_" + effect, &t.post.at(effect), 0, final_format, view_as::rgb});
  }
  for (const auto& [name, from, index, f, how] : wanted) {
    std::vector<texel> got;
    if (auto ok = texels(*from, index, got); !ok) return ok;
    out.buffers.push_back({name, to_image(got, f, w, h, how, s.view.near_plane, s.view.far_plane)});
  }
  if (t.shadow_picture.mapped) {
    std::vector<texel> picture(std::size_t(o.shadow_size) * std::size_t(o.shadow_size));
    const auto* bytes = static_cast<const std::uint8_t*>(t.shadow_picture.mapped);
    for (std::size_t i = 0; i < picture.size(); ++i) std::memcpy(picture[i].data(), bytes + 4 * i, 4);
    out.buffers.push_back({"shadow_colour", to_image(picture, format::rgba8, o.shadow_size, o.shadow_size, view_as::rgb)});
  }
  return true;
}

}  // namespace

result<frame> run_vk(vk::device& dev, const scene& s, const options& o, const pass_shaders& shaders) {
  auto meshes = vk::scene_geometry::create(dev, s);
  if (!meshes) return failure{meshes.error()};
  auto r = vk::renderer::create(dev, s, o, shaders, (*meshes)->input());
  if (!r) return failure{r.error()};
  std::vector<std::map<std::string, double>> frames;
  std::vector<double> totals;
  frame out;
  for (int n = 0; n < std::max(o.frames, 1); ++n) {
    dev.submit([&](VkCommandBuffer cmd) { (*r)->record(cmd, s.view, [&](VkCommandBuffer c, const scheduled_pass& pass) { (**meshes)(c, pass); }); });
    const frame_times t = (*r)->times();
    frames.push_back(t.pass_ms);
    totals.push_back(t.frame_ms);
    out.schedule = t.schedule;
  }
  summarize(frames, totals, out);
  if (auto ok = read_back(dev, **r, s, out); !ok) return failure{ok.error()};
  return out;
}

result<std::vector<frame>> run_vk_sequence(vk::device& dev, const std::vector<scene>& frames, const options& o,
                                           const pass_shaders& shaders) {
  std::vector<frame> out;
  if (frames.empty()) return out;
  auto r = vk::renderer::create(dev, frames.front(), o, shaders, vk::vertex_input::streams(has_texture_coordinates(frames.front())));
  if (!r) return failure{r.error()};
  const std::vector<std::size_t> from = first_with_same_objects(frames);
  std::vector<std::unique_ptr<vk::scene_geometry>> uploaded(frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const scene& s = frames[i];
    if (from[i] == i) {
      auto made = vk::scene_geometry::create(dev, s);
      if (!made) return failure{made.error()};
      uploaded[i] = std::move(*made);
    }
    const vk::scene_geometry& meshes = *uploaded[from[i]];
    dev.submit([&](VkCommandBuffer cmd) { (*r)->record(cmd, s.view, [&](VkCommandBuffer c, const scheduled_pass& pass) { meshes(c, pass); }); });
    const frame_times t = (*r)->times();
    frame f;
    f.schedule = t.schedule;
    summarize({t.pass_ms}, {t.frame_ms}, f);
    if (auto ok = read_back(dev, **r, s, f); !ok) return failure{ok.error()};
    out.push_back(std::move(f));
  }
  return out;
}

result<cli::frame_clock> vk_clock(vk::device& dev, const std::vector<scene>& frames, const options& o, const pass_shaders& shaders) {
  if (frames.empty()) return failure{"a frame clock needs at least one frame"};
  struct running {
    std::unique_ptr<vk::renderer> renderer;
    std::vector<std::shared_ptr<vk::scene_geometry>> meshes;  // a frame each; frames with the same objects share one
    std::vector<camera> views;
    std::size_t next = 0;
  };
  auto on = std::make_shared<running>();
  const std::vector<std::size_t> from = first_with_same_objects(frames);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (from[i] == i) {
      auto made = vk::scene_geometry::create(dev, frames[i]);
      if (!made) return failure{made.error()};
      on->meshes.push_back(std::move(*made));
    } else {
      on->meshes.push_back(on->meshes[from[i]]);
    }
    on->views.push_back(frames[i].view);
  }
  auto r = vk::renderer::create(dev, frames.front(), o, shaders, on->meshes.front()->input());
  if (!r) return failure{r.error()};
  on->renderer = std::move(*r);
  return cli::frame_clock([on, &dev]() -> result<frame_times> {
    const std::size_t i = on->next++ % on->views.size();
    dev.submit([&](VkCommandBuffer cmd) {
      on->renderer->record(cmd, on->views[i], [&](VkCommandBuffer c, const scheduled_pass& pass) { (*on->meshes[i])(c, pass); });
    });
    return on->renderer->times();
  });
}

cli::copy_clock vk_copy_clock(vk::device& dev) {
  struct objects {
    vk::device& dev;
    vk::image from;
    vk::targets to;
    vk::pipeline copy;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
    ~objects() {
      if (pool) vkDestroyDescriptorPool(dev.ctx().device, pool, dev.ctx().allocator);
      dev.destroy(copy);
      dev.destroy(from);
      dev.destroy(to);
    }
  };
  static constexpr int width = 1024, rows = 2048;  // 32 MiB of RGBA32F each
  static constexpr std::size_t row_bytes = std::size_t(width) * 16u, chunk = row_bytes * rows;
  auto t = std::shared_ptr<objects>(new objects{dev, {}, {}, {}});
  return [t](std::size_t bytes) -> result<double> {
    vk::device& d = t->dev;
    if (!t->copy.handle) {
      auto vs = d.get_shader(glsl::fullscreen_vertex_shader(), spirv::stage::vertex, "copy limit (vertex)");
      if (!vs) return failure{vs.error()};
      auto fs = d.get_shader(cli::copy_fragment_shader(), spirv::stage::fragment, "copy limit (fragment)");
      if (!fs) return failure{fs.error()};
      auto p = d.make_graphics_pipeline(**vs, **fs, {format::rgba32f}, "copy limit");
      if (!p) return failure{p.error()};
      t->copy = *p;
      auto from = d.make_storage_image(VK_FORMAT_R32G32B32A32_SFLOAT, width, rows, "copy source");
      if (!from) return failure{from.error()};
      t->from = *from;
      auto to = d.make_targets({{format::rgba32f, {"r", "g", "b", "a"}}}, width, rows, "copy destination", false);
      if (!to) return failure{to.error()};
      t->to = *to;
      VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1};
      VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
      pci.maxSets = 1;
      pci.poolSizeCount = 1;
      pci.pPoolSizes = &size;
      if (vkCreateDescriptorPool(d.ctx().device, &pci, d.ctx().allocator, &t->pool) != VK_SUCCESS) return failure{"no descriptor pool"};
      VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
      ai.descriptorPool = t->pool;
      ai.descriptorSetCount = 1;
      ai.pSetLayouts = &t->copy.set_layout;
      if (vkAllocateDescriptorSets(d.ctx().device, &ai, &t->set) != VK_SUCCESS) return failure{"no descriptor set"};
      const VkDescriptorImageInfo info{VK_NULL_HANDLE, t->from.view, VK_IMAGE_LAYOUT_GENERAL};
      VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      write.dstSet = t->set;
      write.descriptorCount = 1;
      write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
      write.pImageInfo = &info;
      vkUpdateDescriptorSets(d.ctx().device, 1, &write, 0, nullptr);
      d.submit([&](VkCommandBuffer cmd) {  // defined texels to read
        const VkClearColorValue zero{};
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd, t->from.handle, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);
      });
    }
    return d.submit([&](VkCommandBuffer cmd) {
      VkMemoryBarrier ready{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                            VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT};
      for (std::size_t left = bytes; left > 0; left -= std::min(left, chunk)) {
        // Each copy after what wrote its texels before: the clear, or the copy before it.
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                             VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, 1, &ready, 0,
                             nullptr, 0, nullptr);
        d.begin_rendering(cmd, t->to, {});
        const VkRect2D rows_copied{{0, 0}, {std::uint32_t(width), std::uint32_t((std::min(left, chunk) + row_bytes - 1) / row_bytes)}};
        vkCmdSetScissor(cmd, 0, 1, &rows_copied);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, t->copy.handle);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, t->copy.layout, 0, 1, &t->set, 0, nullptr);
        vkCmdDraw(cmd, 3, 1, 0, 0);
        d.end_rendering(cmd);
      }
    });
  };
}

}  // namespace dstrans::render

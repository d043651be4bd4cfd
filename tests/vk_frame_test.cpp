// The Vulkan frame executor (dstrans_vk_frame.hpp) as an engine runs it: frames recorded into the
// engine's command buffers and submitted by the engine, two in flight, resized, and drawn with the
// engine's own vertex layout; under the validation layer.
#include <catch2/catch.hpp>

#include <cstddef>
#include <string>
#include <vector>

#include <dstrans_vk_device.hpp>
#include <dstrans_vk_frame.hpp>
#include "frame_scenes.hpp"

using namespace dstrans;

namespace {

using frame_tests::example;
using frame_tests::sized;

// The engine's side: its device, a command pool, and a command buffer and fence a frame in flight.
struct engine {
  std::unique_ptr<vk::headless_device> hd;
  std::unique_ptr<vk::device> dev;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer cmd[2] = {};
  VkFence fence[2] = {};
  bool open() {
    auto h = vk::headless_device::create(true);
    if (!h) {
      WARN("skipped VK: " << h.error());
      return false;
    }
    hd = std::move(*h);
    auto d = vk::device::create(hd->ctx());
    REQUIRE(d);
    dev = std::move(*d);
    const VkDevice device = hd->ctx().device;
    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pci.queueFamilyIndex = hd->ctx().queue_family;
    vkCreateCommandPool(device, &pci, nullptr, &pool);
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 2;
    vkAllocateCommandBuffers(device, &ai, cmd);
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fci.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    for (VkFence& f : fence) vkCreateFence(device, &fci, nullptr, &f);
    return true;
  }
  ~engine() {
    if (!hd) return;
    const VkDevice device = hd->ctx().device;
    vkDeviceWaitIdle(device);
    for (VkFence f : fence) vkDestroyFence(device, f, nullptr);
    vkDestroyCommandPool(device, pool, nullptr);
  }
  // Frame `n` in flight slot n % 2: waits for the slot's last submission, records, submits, returns.
  void frame(int n, const std::function<void(VkCommandBuffer)>& record) {
    const std::size_t k = std::size_t(n % 2);
    const VkDevice device = hd->ctx().device;
    vkWaitForFences(device, 1, &fence[k], VK_TRUE, UINT64_MAX);
    vkResetFences(device, 1, &fence[k]);
    vkResetCommandBuffer(cmd[k], 0);
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(cmd[k], &bi);
    record(cmd[k]);
    vkEndCommandBuffer(cmd[k]);
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd[k];
    vkQueueSubmit(hd->ctx().queue, 1, &si, fence[k]);
  }
  void idle() { vkDeviceWaitIdle(hd->ctx().device); }
  std::vector<texel> shown(const vk::renderer& r) {
    auto t = dev->read_texels(r.output(), 0, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    INFO(t.error());
    REQUIRE(t);
    return *t;
  }
};

std::unique_ptr<vk::renderer> make(vk::device& dev, const scene& s, const render::options& o,
                                   const vk::vertex_input& v = vk::vertex_input::streams()) {
  auto r = vk::renderer::create(dev, s, o, pass_shaders(), v);
  INFO(r.error());
  REQUIRE(r);
  return std::move(*r);
}

}  // namespace

TEST_CASE("VK renderer: frames recorded into the engine's command buffers, two in flight, resized", "[render][renderer][vk]") {
  engine e;
  if (!e.open()) return;
  for (const char* file : {"glass_room.json", "hair.json", "smoke.json"}) {
    INFO(file);
    const scene s = example(file);
    auto meshes = vk::scene_geometry::create(*e.dev, s);
    REQUIRE(meshes);
    auto draw = [&](VkCommandBuffer cmd, const scheduled_pass& pass) { (**meshes)(cmd, pass); };
    auto r = make(*e.dev, s, sized(64, 36));
    e.frame(0, [&](VkCommandBuffer cmd) { r->record(cmd, s.view, draw); });
    e.idle();
    const std::vector<texel> first = e.shown(*r);
    const frame_times t = r->times();
    CHECK(t.schedule.size() == r->schedule().passes.size());
    CHECK(t.frame_ms > 0.0);
    for (int n = 1; n < 5; ++n) e.frame(n, [&](VkCommandBuffer cmd) { r->record(cmd, s.view, draw); });
    e.idle();
    CHECK(e.shown(*r) == first);

    REQUIRE(r->resize(80, 45));
    e.frame(0, [&](VkCommandBuffer cmd) { r->record(cmd, s.view, draw); });
    auto fresh = make(*e.dev, s, sized(80, 45));
    e.frame(1, [&](VkCommandBuffer cmd) { fresh->record(cmd, s.view, draw); });
    e.idle();
    CHECK(e.shown(*r) == e.shown(*fresh));
    CHECK(!r->resize(0, 45));
  }
  for (const std::string& m : e.hd->validation_messages()) UNSCOPED_INFO(m);
  CHECK(e.hd->validation_messages().empty());
}

TEST_CASE("VK renderer: the engine's own vertex layout draws the frame scene_geometry draws", "[render][renderer][vk]") {
  engine e;
  if (!e.open()) return;
  // One interleaved stream, an object a buffer, as an engine might keep its meshes.
  struct vertex {
    glm::vec3 position;
    std::uint32_t material;
    glm::vec3 normal;
  };
  vk::vertex_input interleaved;
  interleaved.bindings = {{0, sizeof(vertex), VK_VERTEX_INPUT_RATE_VERTEX}};
  interleaved.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, std::uint32_t(offsetof(vertex, position))},
                            {1, 0, VK_FORMAT_R32G32B32_SFLOAT, std::uint32_t(offsetof(vertex, normal))},
                            {2, 0, VK_FORMAT_R32_UINT, std::uint32_t(offsetof(vertex, material))}};
  for (const auto& [file, method] : {std::pair{"glass_room.json", render::technique::interlaced}, std::pair{"hair.json", render::technique::interlaced},
                                     std::pair{"glass_room.json", render::technique::forward},
                                     std::pair{"glass_room_lamp.json", render::technique::interlaced}}) {
    INFO(file << ", " << render::technique_name(method));
    const scene s = example(file);
    render::options o = sized(64, 36);
    o.method = method;
    // scene_geometry culls each pass's objects against its clip volume, the engine here draws them all.
    auto meshes = vk::scene_geometry::create(*e.dev, s);
    REQUIRE(meshes);
    auto reference = make(*e.dev, s, o);
    e.frame(0, [&](VkCommandBuffer cmd) { reference->record(cmd, s.view, [&](VkCommandBuffer c, const scheduled_pass& p) { (**meshes)(c, p); }); });
    struct object_mesh {
      vk::buffer vertices, indices;
      std::uint32_t count = 0;
      bool hair = false;
    };
    std::vector<object_mesh> objects;
    for (const object& ob : s.objects) {
      scene one = s;
      one.objects = {ob};
      const scene_mesh m = flatten(one);
      std::vector<vertex> v;
      for (std::size_t i = 0; i < m.positions.size(); ++i) v.push_back({m.positions[i], m.materials[i], m.normals[i]});
      object_mesh om;
      om.hair = m.hair_first == 0 && !m.indices.empty();
      om.count = std::uint32_t(m.indices.size());
      auto vb = e.dev->make_buffer(std::max<std::size_t>(v.size(), 1) * sizeof(vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "engine vertices");
      auto ib = e.dev->make_buffer(std::max<std::size_t>(m.indices.size(), 1) * 4, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "engine indices");
      REQUIRE(vb);
      REQUIRE(ib);
      if (!v.empty()) std::memcpy(vb->mapped, v.data(), v.size() * sizeof(vertex));
      if (!m.indices.empty()) std::memcpy(ib->mapped, m.indices.data(), m.indices.size() * 4);
      om.vertices = *vb;
      om.indices = *ib;
      objects.push_back(om);
    }
    auto own = make(*e.dev, s, o, interleaved);
    std::vector<std::string> asked;
    e.frame(1, [&](VkCommandBuffer cmd) {
      own->record(cmd, s.view, [&](VkCommandBuffer c, const scheduled_pass& pass) {
        asked.push_back(pass.label);
        // Surfaces before hair, as flatten orders them: the same fragments in the same order.
        for (const bool hair : {false, true}) {
          if ((hair && pass.draws == geometry_set::surfaces) || (!hair && pass.draws == geometry_set::hair)) continue;
          for (const object_mesh& om : objects)
            if (om.hair == hair && om.count) {
              const VkDeviceSize zero = 0;
              vkCmdBindVertexBuffers(c, 0, 1, &om.vertices.handle, &zero);
              vkCmdBindIndexBuffer(c, om.indices.handle, 0, VK_INDEX_TYPE_UINT32);
              vkCmdDrawIndexed(c, om.count, 1, 0, 0, 0);
            }
        }
      });
    });
    e.idle();
    CHECK(e.shown(*own) == e.shown(*reference));
    std::vector<std::string> geometry;
    for (const scheduled_pass& pass : own->schedule().passes)
      if (pass.draws != geometry_set::none) geometry.push_back(pass.label);
    CHECK(asked == geometry);
    for (object_mesh& om : objects) {
      e.dev->destroy(om.vertices);
      e.dev->destroy(om.indices);
    }
  }
  for (const std::string& m : e.hd->validation_messages()) UNSCOPED_INFO(m);
  CHECK(e.hd->validation_messages().empty());
}

TEST_CASE("VK renderer: temporal interlacing leaves nothing where a pane moved away", "[render][renderer][vk][temporal]") {
  engine e;
  if (!e.open()) return;
  const frame_tests::moved_pane m = frame_tests::moved_pane_scenes();
  render::options o = sized(160, 90);
  o.temporal = true;
  auto before = vk::scene_geometry::create(*e.dev, m.before), after = vk::scene_geometry::create(*e.dev, m.after),
       without = vk::scene_geometry::create(*e.dev, m.without);
  REQUIRE((before && after && without));
  // Every renderer describes the scene after the move, so that all draw the same shadows.
  auto first = [&](const vk::scene_geometry& g) {
    auto r = make(*e.dev, m.after, o);
    e.frame(0, [&](VkCommandBuffer cmd) { r->record(cmd, m.after.view, [&](VkCommandBuffer c, const scheduled_pass& p) { g(c, p); }); });
    e.idle();
    return e.shown(*r);
  };
  auto r = make(*e.dev, m.after, o);
  e.frame(0, [&](VkCommandBuffer cmd) { r->record(cmd, m.after.view, [&](VkCommandBuffer c, const scheduled_pass& p) { (**before)(c, p); }); });
  e.frame(1, [&](VkCommandBuffer cmd) { r->record(cmd, m.after.view, [&](VkCommandBuffer c, const scheduled_pass& p) { (**after)(c, p); }); });
  e.idle();
  frame_tests::check_nothing_left(e.shown(*r), first(**after), first(**before), first(**without), 160, 90);
  for (const std::string& msg : e.hd->validation_messages()) UNSCOPED_INFO(msg);
  CHECK(e.hd->validation_messages().empty());
}

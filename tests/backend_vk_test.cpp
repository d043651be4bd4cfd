// The Vulkan backend on a real driver (Mesa lavapipe) under the Khronos validation layer: formulas agree
// with the CPU, G-buffers hold exactly the CPU's bytes, bad input gives sentences, and any validation
// message fails the test. Skips with a message without a Vulkan device.
#include <catch2/catch.hpp>

#include <cstring>

#include <dstrans_vk.hpp>
#include <dstrans_vk_device.hpp>

#include "backend_checks.hpp"

using namespace dstrans;

namespace {

// A validated device and dstrans's objects on it, for one test case; empty where there is none.
struct vk_fixture {
  std::unique_ptr<vk::headless_device> hd;
  std::unique_ptr<vk::device> dev;
  ~vk_fixture() {
    dev.reset();
    if (hd) check_quiet();
  }
  void check_quiet() {
    const auto messages = hd->validation_messages();
    for (const auto& m : messages) UNSCOPED_INFO(m);
    CHECK(messages.empty());
  }
};

bool open(vk_fixture& fx) {
  auto hd = vk::headless_device::create(true);
  if (!hd) {
    WARN("skipped: no validated Vulkan device here: " << hd.error());
    return false;
  }
  fx.hd = std::move(*hd);
  auto dev = vk::device::create(fx.hd->ctx());
  REQUIRE(dev);
  fx.dev = std::move(*dev);
  return true;
}

template <class L>
void check_gbuffer_write(vk::device& dev, int width, int height, bool exact) {
  const auto raw = testing::test_surfaces(width, height);
  const auto surfaces = exact ? testing::on_grid<L>(raw) : raw;
  auto targets = dev.make_targets(describe<L>(), width, height, "test gbuffer", false);
  REQUIRE(targets);
  auto vs = dev.get_shader(glsl::fullscreen_vertex_shader(), spirv::stage::vertex, "fullscreen");
  auto fs = dev.get_shader(testing::gbuffer_writer<L>(width), spirv::stage::fragment, "gbuffer write");
  REQUIRE(vs);
  REQUIRE(fs);
  auto pipe = dev.make_graphics_pipeline(**vs, **fs, targets->formats, "gbuffer write");
  REQUIRE(pipe);
  words packed;
  for (const surface& s : surfaces) put(s, packed);
  auto buf = dev.make_buffer(packed.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "surfaces");
  REQUIRE(buf);
  std::memcpy(buf->mapped, packed.data(), packed.size() * 4);

  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
  VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, nullptr, 0, 1, 1, &size};
  VkDescriptorPool pool = VK_NULL_HANDLE;
  vkCreateDescriptorPool(dev.ctx().device, &pci, nullptr, &pool);
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO, nullptr, pool, 1, &pipe->set_layout};
  VkDescriptorSet set = VK_NULL_HANDLE;
  vkAllocateDescriptorSets(dev.ctx().device, &ai, &set);
  VkDescriptorBufferInfo bi{buf->handle, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = set;
  w.descriptorCount = 1;
  w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  w.pBufferInfo = &bi;
  vkUpdateDescriptorSets(dev.ctx().device, 1, &w, 0, nullptr);
  const double ms = dev.submit([&](VkCommandBuffer cmd) {
    dev.begin_rendering(cmd, *targets, std::vector<glm::vec4>(targets->colors.size(), glm::vec4(0.0f)));
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe->handle);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe->layout, 0, 1, &set, 0, nullptr);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    dev.end_rendering(cmd);
  });
  CHECK(ms >= 0.0);
  testing::check_texels<L>(surfaces, exact, [&](int t) {
    auto texels = dev.read_texels(*targets, t);
    REQUIRE(texels);
    return *texels;
  });
  vkDestroyDescriptorPool(dev.ctx().device, pool, nullptr);
  dev.destroy(*buf);
  dev.destroy(*pipe);
  dev.destroy(*targets);
}

}  // namespace

TEST_CASE("VK: every formula agrees with the CPU on 10,000 inputs", "[vk][formula]") {
  vk_fixture fx;
  if (!open(fx)) return;
  INFO(fx.hd->name());
  testing::check_every_formula([&](const formula& f, const words& a, std::size_t n) { return fx.dev->run_formula(f, a, n); });
}

TEST_CASE("VK: a batch past the dispatch limit runs in several dispatches, every result right", "[vk][formula]") {
  vk_fixture fx;
  if (!open(fx)) return;
  testing::check_large_batch([&](const formula& f, const words& a, std::size_t n) { return fx.dev->run_formula(f, a, n); });
}

TEST_CASE("VK: every formula's result is finite and within its physical range for 100,000 inputs", "[vk][property]") {
  vk_fixture fx;
  if (!open(fx)) return;
  testing::check_every_property([&](const formula& f, const words& a, std::size_t n) { return fx.dev->run_formula(f, a, n); });
}

TEST_CASE("VK: a G-buffer written by a shader holds the CPU's bytes (on the grid) or permitted ones", "[vk][layout]") {
  vk_fixture fx;
  if (!open(fx)) return;
  for (bool exact : {true, false}) {
    check_gbuffer_write<thesis_gbuffer>(*fx.dev, 37, 23, exact);
    check_gbuffer_write<testing::float_layout>(*fx.dev, 37, 23, exact);
    check_gbuffer_write<thesis_shadow_map>(*fx.dev, 16, 9, exact);
    check_gbuffer_write<compact_gbuffer>(*fx.dev, 37, 23, exact);
  }
}

TEST_CASE("VK: clear errors for layouts the device cannot hold, bad shaders and mismatched pipelines", "[vk]") {
  vk_fixture fx;
  if (!open(fx)) return;
  vk::device& dev = *fx.dev;
  std::vector<target_desc> many(9, target_desc{format::r8, {"unused"}});
  auto too_many = dev.make_targets(many, 8, 8, "wide", false);
  REQUIRE_FALSE(too_many);
  CHECK_THAT(too_many.error(), Catch::Contains("9 render targets") && Catch::Contains("at most"));
  auto empty = dev.make_targets(describe<thesis_gbuffer>(), 8, 0, "empty", false);
  REQUIRE_FALSE(empty);
  CHECK_THAT(empty.error(), Catch::Contains("8x0 is not a size"));

  glsl::source broken;
  broken.add("layout(location = 0) out vec4 o;\nvoid main() {\n  o = vec4(missing_value);\n}\n", "broken.frag", 10);
  auto bad = dev.get_shader(broken, spirv::stage::fragment, "broken");
  REQUIRE_FALSE(bad);
  CHECK_THAT(bad.error(), Catch::Contains("broken.frag:12:") && Catch::Contains("missing_value"));

  // A shader that writes the thesis G-buffer cannot draw into the light buffer: caught before building.
  auto vs = dev.get_shader(glsl::fullscreen_vertex_shader(), spirv::stage::vertex, "fullscreen");
  auto fs = dev.get_shader(testing::gbuffer_writer<thesis_gbuffer>(8), spirv::stage::fragment, "gbuffer write");
  REQUIRE(vs);
  REQUIRE(fs);
  auto mismatch = dev.make_graphics_pipeline(**vs, **fs, {format::rgba8}, "mismatch");
  REQUIRE_FALSE(mismatch);
  CHECK_THAT(mismatch.error(), Catch::Contains("writes 4 outputs") && Catch::Contains("1 targets"));
  auto wrong_width = dev.make_graphics_pipeline(**vs, **fs, {format::rgba8, format::rgb10a2, format::rgba8, format::rg32f},
                                                "wrong width");
  REQUIRE_FALSE(wrong_width);
  CHECK_THAT(wrong_width.error(), Catch::Contains("does not match target 3 (RG32F)"));

  // Material textures past the device's array layers are refused before anything is allocated; a scene's are made.
  texture_array wide;
  wide.width = wide.height = 1;
  wide.layers = 1 << 20;
  wide.levels = {std::vector<std::uint8_t>(4)};
  auto past = dev.make_texture_array(wide, "wide textures");
  REQUIRE_FALSE(past);
  CHECK_THAT(past.error(), Catch::StartsWith("wide textures: 1048576 layers of 1 x 1") && Catch::Contains("exceed the device's array images"));
  scene textured;
  textured.textures.push_back({2, 2, std::vector<std::uint8_t>(16, 255)});
  auto made = dev.make_texture_array(texture_array_of(textured), "textures");
  INFO(made.error());
  REQUIRE(made);
  CHECK(made->view != VK_NULL_HANDLE);
  dev.destroy(*made);

  // The same text compiles once: the cache hands back the same module.
  auto again = dev.get_shader(glsl::fullscreen_vertex_shader(), spirv::stage::vertex, "fullscreen again");
  REQUIRE(again);
  CHECK(*again == *vs);
}

TEST_CASE("VK: clip-space +y is the image's top row and counter-clockwise triangles face the viewer", "[vk]") {
  vk_fixture fx;
  if (!open(fx)) return;
  vk::device& dev = *fx.dev;
  auto t = dev.make_targets({target_desc{format::rgba8, {"r", "g", "b", "a"}}}, 8, 8, "facing", false);
  REQUIRE(t);
  glsl::source vs, fs;
  vs.add(testing::facing_vertex_shader, __FILE__, __LINE__);
  fs.add(testing::facing_fragment_shader, __FILE__, __LINE__);
  auto v = dev.get_shader(vs, spirv::stage::vertex, "facing");
  auto f = dev.get_shader(fs, spirv::stage::fragment, "facing");
  REQUIRE(v);
  REQUIRE(f);
  vk::pipeline_state culled;
  culled.cull = VK_CULL_MODE_BACK_BIT;
  auto pipe = dev.make_graphics_pipeline(**v, **f, t->formats, "facing", culled);
  REQUIRE(pipe);
  dev.submit([&](VkCommandBuffer cmd) {
    dev.begin_rendering(cmd, *t, {glm::vec4(0.0f)});
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe->handle);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    dev.end_rendering(cmd);
  });
  auto texels = dev.read_texels(*t, 0);
  REQUIRE(texels);
  testing::check_facing(*texels, 8);
  dev.destroy(*pipe);
  dev.destroy(*t);
}

TEST_CASE("VK: many timed passes go in one submission, each timed, and no more than were asked for", "[vk]") {
  vk_fixture fx;
  if (!open(fx)) return;
  vk::device& dev = *fx.dev;
  auto t = dev.make_targets({target_desc{format::rgba8, {"r", "g", "b", "a"}}}, 64, 64, "passes", false);
  REQUIRE(t);
  auto clear = [&](float v) {
    return [&, v](VkCommandBuffer cmd) {
      dev.begin_rendering(cmd, *t, {glm::vec4(v)});
      dev.end_rendering(cmd);
    };
  };
  // The buffer begin_passes returns takes untimed commands between passes; the last pass's clear stays.
  for (std::size_t capacity : {std::size_t(3), std::size_t(40)}) {
    const VkCommandBuffer cmd = dev.begin_passes(capacity);
    dev.record_pass(clear(0.25f));
    clear(0.5f)(cmd);
    dev.record_pass(clear(0.75f));
    dev.record_pass(clear(1.0f));
    auto ms = dev.submit_passes();
    INFO(ms.error());
    REQUIRE(ms);
    REQUIRE(ms->size() == 4);
    double passes = 0.0;
    for (std::size_t k = 0; k < 3; ++k) {
      CHECK((*ms)[k] >= 0.0);
      passes += (*ms)[k];
    }
    CHECK(passes <= ms->back() + 1e-6);  // disjoint intervals inside the submission's
    auto texels = dev.read_texels(*t, 0);
    REQUIRE(texels);
    CHECK((*texels)[0][0] == 255);
  }
  dev.begin_passes(1);
  dev.record_pass(clear(0.0f));
  dev.record_pass(clear(0.0f));
  auto over = dev.submit_passes();
  CHECK(over.error() == "2 passes were recorded into a submission begun for 1");
  dev.destroy(*t);
}

TEST_CASE("VK: images and buffers are slices of shared memory blocks, each freed with its last slice", "[vk]") {
  vk_fixture fx;
  if (!open(fx)) return;
  vk::device& dev = *fx.dev;
  const std::size_t before = dev.memory_blocks();
  std::vector<vk::buffer> buffers;
  for (int k = 0; k < 20; ++k) {
    auto b = dev.make_buffer(1000, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "slice");
    REQUIRE(b);
    buffers.push_back(*b);
  }
  CHECK(dev.memory_blocks() == before + 1);
  for (std::size_t k = 1; k < buffers.size(); ++k) {
    CHECK(buffers[k].memory == buffers[0].memory);
    CHECK(buffers[k].slice.offset >= buffers[k - 1].slice.offset + 1000);  // no two overlap
    std::memset(buffers[k].mapped, int(k), 1000);                          // each its own mapped bytes
  }
  CHECK(static_cast<unsigned char*>(buffers[5].mapped)[999] == 5);
  auto t = dev.make_targets({target_desc{format::rgba8, {"r", "g", "b", "a"}}, target_desc{format::r32f, {"depth"}}}, 64, 64, "slices", true);
  REQUIRE(t);
  CHECK(dev.memory_blocks() == before + 2);  // images apart from buffers
  CHECK(t->colors[0].memory == t->colors[1].memory);
  // A freed slice is taken again; the blocks go when their last slice does.
  const VkDeviceSize freed = buffers[3].slice.offset;
  dev.destroy(buffers[3]);
  auto again = dev.make_buffer(1000, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "slice again");
  REQUIRE(again);
  CHECK(again->slice.offset == freed);
  buffers[3] = *again;
  for (vk::buffer& b : buffers) dev.destroy(b);
  CHECK(dev.memory_blocks() == before + 1);
  auto texels = dev.read_texels(*t, 0);  // the images still work
  CHECK(texels);
  dev.destroy(*t);
  CHECK(dev.memory_blocks() == before);
}

TEST_CASE("VK: the physical devices are listed, and a device is made on one by index or by name", "[vk][device]") {
  const auto devices = vk::headless_device::devices();
  REQUIRE(devices);
  if (devices->empty()) {
    WARN("skipped: no Vulkan device here");
    return;
  }
  auto first = vk::headless_device::create(false);
  REQUIRE(first);
  const std::string name = (*first)->name(), driver = (*first)->driver();
  CHECK(driver.size() > 1);
  CHECK(devices->front().rfind("0: " + name + ", ", 0) == 0);
  CHECK(devices->front().find(driver) != std::string::npos);
  auto by_index = vk::headless_device::create(false, "0");
  REQUIRE(by_index);
  CHECK((*by_index)->name() == name);
  auto by_name = vk::headless_device::create(false, name.substr(0, 4));
  REQUIRE(by_name);
  CHECK((*by_name)->name() == name);
  const auto none = vk::headless_device::create(false, "no such device");
  REQUIRE_FALSE(none);
  CHECK(none.error().find("no Vulkan device named 'no such device'; the devices are:\n  " + devices->front()) == 0);
  const auto out_of_range = vk::headless_device::create(false, std::to_string(devices->size()));
  REQUIRE_FALSE(out_of_range);
  CHECK(out_of_range.error().find("no Vulkan device number") == 0);
}

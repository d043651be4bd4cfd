// A program that takes dstrans the way an engine would: the core, both backends, and the whole frame on
// each with its own meshes (GL: its vertex arrays; Vulkan: its vertex layout and command buffer); exits 0
// when they work and the two frames agree.
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>

#include <dstrans/dstrans.hpp>
#include <dstrans_gl.hpp>
#include <dstrans_gl_context.hpp>
#include <dstrans_gl_frame.hpp>
#include <dstrans_spirv.hpp>
#include <dstrans_vk_device.hpp>
#include <dstrans_vk_frame.hpp>

namespace {

// The engine's world: a floor, a glass pane, hair and smoke under the sun and a shadowing spot light,
// anti-aliased.
dstrans::scene world() {
  dstrans::scene s;
  s.materials = {dstrans::material{}, dstrans::material{}, dstrans::material{}, dstrans::material{}};
  s.materials[1].diffuse = {0.2f, 0.4f, 1.0f};
  s.materials[1].alpha = 0.4f;
  s.materials[1].refractive = true;
  s.materials[2].diffuse = {0.5f, 0.3f, 0.1f};
  s.materials[2].alpha = 0.5f;
  s.materials[2].hair = true;
  s.materials[3].alpha = 0.3f;
  s.objects.push_back({dstrans::shape_box({4.0f, 0.1f, 4.0f}), glm::mat4(1.0f), 0});
  s.objects.push_back({dstrans::shape_pane({1.5f, 1.5f}), glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.0f, 0.5f)), 1});
  s.objects.push_back({dstrans::shape_hair(0.3f, 40, 0.8f, 0.01f, 4, 7), glm::translate(glm::mat4(1.0f), glm::vec3(-1.0f, 0.1f, 0.0f)), 2});
  dstrans::light spot;
  spot.kind = dstrans::light_kind::spot;
  spot.position = {0.0f, 4.0f, 2.0f};
  spot.direction = glm::normalize(glm::vec3(0.0f, -1.0f, -0.4f));
  spot.shadows = true;
  s.view.position = {0.0f, 3.0f, 3.5f};
  s.view.target = {0.0f, 0.5f, 0.0f};
  dstrans::light sun;
  sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.5f));
  s.lights = {sun, spot};
  dstrans::particle_system smoke;
  smoke.material = 3;
  smoke.base = {1.0f, 0.1f, 0.0f};
  smoke.count = 30;
  s.particles = {smoke};
  dstrans::post_effect aa;
  aa.kind = dstrans::post_kind::antialias;
  s.post = {aa};
  return s;
}

// Each object as the engine keeps it: world-space vertices of position, material and normal, interleaved.
struct vertex {
  glm::vec3 position;
  std::uint32_t material;
  glm::vec3 normal;
};
struct object_mesh {
  std::vector<vertex> vertices;
  std::vector<std::uint32_t> indices;
  dstrans::material material;
};
std::vector<object_mesh> meshes_of(const dstrans::scene& s) {
  std::vector<object_mesh> out;
  for (const dstrans::object& ob : s.objects) {
    object_mesh m;
    m.material = s.materials[ob.material];
    for (std::size_t i = 0; i < ob.geometry.positions.size(); ++i) {
      const glm::mat3 t(ob.transform), n = m.material.hair ? t : glm::transpose(glm::inverse(t));
      m.vertices.push_back({glm::vec3(ob.transform * glm::vec4(ob.geometry.positions[i], 1.0f)), ob.material,
                            glm::normalize(n * ob.geometry.normals[i])});
    }
    m.indices = ob.geometry.indices;
    out.push_back(m);
  }
  return out;
}
// Whether the engine draws `m` in `pass`: surfaces before hair, as the renderers order them.
bool drawn(const object_mesh& m, bool hair_round, const dstrans::scheduled_pass& pass) {
  return m.material.hair == hair_round && dstrans::draws(pass.draws, m.material);
}

dstrans::render::options small() {
  dstrans::render::options o;
  o.width = 64;
  o.height = 36;
  o.shadow_size = 256;
  o.opaque_shadows_depth_only = true;  // drawn() tells opaque materials from the rest
  return o;
}

// The frame on GL with the engine's vertex arrays; empty where there is no GL.
std::vector<dstrans::texel> gl_frame(const dstrans::scene& s, const std::vector<object_mesh>& meshes, bool& ok) {
  auto ctx = dstrans::gl::headless_context::create();
  if (!ctx) {
    std::printf("dstrans consumer: no GL here (%s)\n", ctx.error().c_str());
    return {};
  }
  auto r = dstrans::gl::renderer::create(s, small());
  if (!r) {
    std::printf("dstrans consumer: %s\n", r.error().c_str());
    ok = false;
    return {};
  }
  std::vector<GLuint> vaos(meshes.size()), buffers(2 * meshes.size());
  glCreateVertexArrays(GLsizei(vaos.size()), vaos.data());
  glCreateBuffers(GLsizei(buffers.size()), buffers.data());
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    glNamedBufferStorage(buffers[2 * k], GLsizeiptr(meshes[k].vertices.size() * sizeof(vertex)), meshes[k].vertices.data(), 0);
    glNamedBufferStorage(buffers[2 * k + 1], GLsizeiptr(meshes[k].indices.size() * 4), meshes[k].indices.data(), 0);
    glVertexArrayVertexBuffer(vaos[k], 0, buffers[2 * k], 0, sizeof(vertex));
    glVertexArrayElementBuffer(vaos[k], buffers[2 * k + 1]);
    for (GLuint a = 0; a < 3; ++a) {
      glEnableVertexArrayAttrib(vaos[k], a);
      glVertexArrayAttribBinding(vaos[k], a, 0);
    }
    glVertexArrayAttribFormat(vaos[k], 0, 3, GL_FLOAT, GL_FALSE, GLuint(offsetof(vertex, position)));
    glVertexArrayAttribFormat(vaos[k], 1, 3, GL_FLOAT, GL_FALSE, GLuint(offsetof(vertex, normal)));
    glVertexArrayAttribIFormat(vaos[k], 2, 1, GL_UNSIGNED_INT, GLuint(offsetof(vertex, material)));
  }
  (*r)->render(s.view, [&](const dstrans::scheduled_pass& pass) {
    for (const bool hair : {false, true})
      for (std::size_t k = 0; k < meshes.size(); ++k)
        if (drawn(meshes[k], hair, pass)) {
          glBindVertexArray(vaos[k]);
          glDrawElements(GL_TRIANGLES, GLsizei(meshes[k].indices.size()), GL_UNSIGNED_INT, nullptr);
        }
  });
  std::vector<dstrans::texel> image = dstrans::gl::read_texels((*r)->output(), 0);
  glDeleteVertexArrays(GLsizei(vaos.size()), vaos.data());
  glDeleteBuffers(GLsizei(buffers.size()), buffers.data());
  return image;
}

// The frame on Vulkan, recorded into the engine's command buffer with its vertex layout; empty where
// there is no Vulkan.
std::vector<dstrans::texel> vk_frame(const dstrans::scene& s, const std::vector<object_mesh>& meshes, bool& ok) {
  auto hd = dstrans::vk::headless_device::create(false);
  if (!hd) {
    std::printf("dstrans consumer: no Vulkan here (%s)\n", hd.error().c_str());
    return {};
  }
  auto dev = dstrans::vk::device::create((*hd)->ctx());
  if (!dev) {
    std::printf("dstrans consumer: %s\n", dev.error().c_str());
    ok = false;
    return {};
  }
  dstrans::vk::vertex_input layout;
  layout.bindings = {{0, sizeof(vertex), VK_VERTEX_INPUT_RATE_VERTEX}};
  layout.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, std::uint32_t(offsetof(vertex, position))},
                       {1, 0, VK_FORMAT_R32G32B32_SFLOAT, std::uint32_t(offsetof(vertex, normal))},
                       {2, 0, VK_FORMAT_R32_UINT, std::uint32_t(offsetof(vertex, material))}};
  auto r = dstrans::vk::renderer::create(**dev, s, small(), dstrans::pass_shaders(), layout);
  if (!r) {
    std::printf("dstrans consumer: %s\n", r.error().c_str());
    ok = false;
    return {};
  }
  std::vector<dstrans::vk::buffer> buffers;
  for (const object_mesh& m : meshes) {
    auto v = (*dev)->make_buffer(m.vertices.size() * sizeof(vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "engine vertices");
    auto i = (*dev)->make_buffer(m.indices.size() * 4, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "engine indices");
    if (!v || !i) return {};
    std::memcpy(v->mapped, m.vertices.data(), m.vertices.size() * sizeof(vertex));
    std::memcpy(i->mapped, m.indices.data(), m.indices.size() * 4);
    buffers.insert(buffers.end(), {*v, *i});
  }
  // The engine's command pool, buffer and fence; it records, submits and waits itself.
  const VkDevice device = (*hd)->ctx().device;
  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr, 0, (*hd)->ctx().queue_family};
  VkCommandPool pool = VK_NULL_HANDLE;
  vkCreateCommandPool(device, &pci, nullptr, &pool);
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, pool, VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  vkAllocateCommandBuffers(device, &ai, &cmd);
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr, VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT, nullptr};
  vkBeginCommandBuffer(cmd, &bi);
  (*r)->record(cmd, s.view, [&](VkCommandBuffer c, const dstrans::scheduled_pass& pass) {
    const VkDeviceSize zero = 0;
    for (const bool hair : {false, true})
      for (std::size_t k = 0; k < meshes.size(); ++k)
        if (drawn(meshes[k], hair, pass)) {
          vkCmdBindVertexBuffers(c, 0, 1, &buffers[2 * k].handle, &zero);
          vkCmdBindIndexBuffer(c, buffers[2 * k + 1].handle, 0, VK_INDEX_TYPE_UINT32);
          vkCmdDrawIndexed(c, std::uint32_t(meshes[k].indices.size()), 1, 0, 0, 0);
        }
  });
  vkEndCommandBuffer(cmd);
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, nullptr, 0};
  VkFence fence = VK_NULL_HANDLE;
  vkCreateFence(device, &fci, nullptr, &fence);
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO, nullptr, 0, nullptr, nullptr, 1, &cmd, 0, nullptr};
  vkQueueSubmit((*hd)->ctx().queue, 1, &si, fence);
  vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX);
  auto image = (*dev)->read_texels((*r)->output(), 0, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  vkDestroyFence(device, fence, nullptr);
  vkDestroyCommandPool(device, pool, nullptr);
  for (dstrans::vk::buffer& b : buffers) (*dev)->destroy(b);
  if (!image) ok = false;
  return image ? *image : std::vector<dstrans::texel>{};
}

}  // namespace

int main() {
  dstrans::glsl::source src;
  dstrans::glsl::add_layout<dstrans::thesis_gbuffer>(src, "gbuffer");
  bool ok = dstrans::thesis_gbuffer::bytes_per_pixel == 16 && src.str().find("dst_gbuffer_write") != std::string::npos &&
            dstrans::interlace::rows::keep({0, 1}, {2, 2});
  // The Vulkan backend's shader compiler takes the generated G-buffer code as a fragment shader.
  src.add("layout(location = 0) in vec3 n;\nvoid main() { dst_surface s = dst_surface_zero(); s.normal = n; "
          "dst_gbuffer_write(s); }\n",
          __FILE__, __LINE__);
  const auto spirv = dstrans::spirv::compile(src, dstrans::spirv::stage::fragment, dstrans::spirv::api::vulkan);
  ok = ok && spirv && !spirv->empty();
  // A pass shader of the reference pipeline, from the text in the package and the slot table.
  dstrans::glsl::source pass;
  dstrans::add_slots(pass);
  const dstrans::pass_shaders shaders;
  for (const char* file : {"frame.glsl", "fragment.glsl", "post.glsl", "post_tone.frag.glsl"})
    ok = ok && shaders.add_to(pass, file, {"DST_SEPIA"});
  const auto pass_spirv = dstrans::spirv::compile(pass, dstrans::spirv::stage::fragment, dstrans::spirv::api::vulkan);
  if (!pass_spirv) std::printf("dstrans consumer: %s\n", pass_spirv.error().c_str());
  ok = ok && pass_spirv && !pass_spirv->empty();
  // The GL backend makes Table 3.1's targets where this machine has EGL.
  if (auto ctx = dstrans::gl::headless_context::create()) {
    auto t = dstrans::gl::make_targets(dstrans::describe<dstrans::thesis_gbuffer>(), 8, 8, "consumer gbuffer", true);
    ok = ok && t && t->textures.size() == 4;
    if (t) dstrans::gl::destroy(*t);
  } else {
    std::printf("dstrans consumer: no GL here (%s)\n", ctx.error().c_str());
  }
  // The whole frame on each backend that is here, with the engine's meshes: both draw the same picture.
  const dstrans::scene s = world();
  const std::vector<object_mesh> meshes = meshes_of(s);
  const std::vector<dstrans::texel> on_gl = gl_frame(s, meshes, ok), on_vk = vk_frame(s, meshes, ok);
  for (const std::vector<dstrans::texel>* image : {&on_gl, &on_vk}) {
    std::size_t lit = 0;
    for (const dstrans::texel& t : *image) lit += t[0] + t[1] + t[2] > 30;
    if (!image->empty() && lit < image->size() / 5) {
      std::printf("dstrans consumer: a frame is dark (%zu of %zu pixels lit)\n", lit, image->size());
      ok = false;
    }
  }
  if (!on_gl.empty() && !on_vk.empty()) {
    double sum = 0.0;
    for (std::size_t i = 0; i < on_gl.size() && on_gl.size() == on_vk.size(); ++i)
      for (int c = 0; c < 3; ++c) sum += std::pow(double(on_gl[i][c]) - double(on_vk[i][c]), 2.0);
    const double rmse = on_gl.size() == on_vk.size() ? std::sqrt(sum / double(3 * on_gl.size())) : 255.0;
    std::printf("dstrans consumer: GL and Vulkan frames differ by RMSE %.3f\n", rmse);
    ok = ok && rmse < 1.0;
  }
  std::puts(ok ? "dstrans consumer: ok" : "dstrans consumer: WRONG");
  return ok ? 0 : 1;
}

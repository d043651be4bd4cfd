// A program that takes dstrans the way an engine would: the core, and both backends; exits 0 when they work.
#include <cstdio>

#include <dstrans/dstrans.hpp>
#include <dstrans_gl.hpp>
#include <dstrans_gl_context.hpp>
#include <dstrans_spirv.hpp>
#include <dstrans_vk_device.hpp>

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
  // The Vulkan backend opens a device where this machine has one.
  if (auto dev = dstrans::vk::headless_device::create(false); !dev)
    std::printf("dstrans consumer: no Vulkan here (%s)\n", dev.error().c_str());
  std::puts(ok ? "dstrans consumer: ok" : "dstrans consumer: WRONG");
  return ok ? 0 : 1;
}

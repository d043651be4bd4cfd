// Implements gpu.hpp.
#include "gpu.hpp"

namespace dstrans::cli {

result<std::unique_ptr<gpu>> open_gpu(const std::string& backend) {
  auto g = std::make_unique<gpu>();
  if (backend == "gl") {
#ifdef DSTRANS_HAVE_GL
    auto ctx = gl::headless_context::create();
    if (!ctx) return failure{"no OpenGL: " + ctx.error()};
    g->gl = std::move(*ctx);
    return g;
#else
    return failure{"this dstrans was built without the OpenGL backend (DSTRANS_BUILD_GL=OFF)"};
#endif
  }
#ifdef DSTRANS_HAVE_VK
  auto hd = vk::headless_device::create(false);
  if (!hd) return failure{"no Vulkan: " + hd.error()};
  g->vk_instance = std::move(*hd);
  auto dev = vk::device::create(g->vk_instance->ctx());
  if (!dev) return failure{"no Vulkan: " + dev.error()};
  g->vk = std::move(*dev);
  return g;
#else
  return failure{"this dstrans was built without the Vulkan backend (DSTRANS_BUILD_VK=OFF)"};
#endif
}

}  // namespace dstrans::cli

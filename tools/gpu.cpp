// Implements gpu.hpp.
#include "gpu.hpp"

namespace dstrans::cli {

result<std::unique_ptr<gpu>> open_gpu(const std::string& backend, const std::string& device) {
  auto g = std::make_unique<gpu>();
  if (backend == "gl") {
#ifdef DSTRANS_HAVE_GL
    auto ctx = gl::headless_context::create(device);
    if (!ctx) return failure{"no OpenGL: " + ctx.error()};
    g->gl = std::move(*ctx);
    g->device = g->gl->renderer();
    g->driver = g->gl->version();
    return g;
#else
    return failure{"this dstrans was built without the OpenGL backend (DSTRANS_BUILD_GL=OFF)"};
#endif
  }
#ifdef DSTRANS_HAVE_VK
  auto hd = vk::headless_device::create(false, device);
  if (!hd) return failure{"no Vulkan: " + hd.error()};
  g->vk_instance = std::move(*hd);
  g->device = g->vk_instance->name();
  g->driver = g->vk_instance->driver();
  auto dev = vk::device::create(g->vk_instance->ctx());
  if (!dev) return failure{"no Vulkan: " + dev.error()};
  g->vk = std::move(*dev);
  return g;
#else
  return failure{"this dstrans was built without the Vulkan backend (DSTRANS_BUILD_VK=OFF)"};
#endif
}

std::string device_list() {
  std::string out;
  auto add = [&](const char* api, const result<std::vector<std::string>>& devices) {
    out += std::string(api) + ":\n";
    if (!devices) out += "  none: " + devices.error() + "\n";
    else if (devices->empty()) out += "  none\n";
    else
      for (const std::string& d : *devices) out += "  " + d + "\n";
  };
#ifdef DSTRANS_HAVE_GL
  add("OpenGL (EGL devices; without --device, Mesa's surfaceless platform)", gl::headless_context::devices());
#endif
#ifdef DSTRANS_HAVE_VK
  add("Vulkan", vk::headless_device::devices());
#endif
  return out;
}

}  // namespace dstrans::cli

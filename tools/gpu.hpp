// A headless GPU for the command line: an OpenGL 4.5 context or a Vulkan device with dstrans's objects
// on it, whichever the build has and the machine offers.
#pragma once

#include <memory>
#include <string>

#include <dstrans/result.hpp>

#ifdef DSTRANS_HAVE_GL
#include <dstrans_gl_context.hpp>
#endif
#ifdef DSTRANS_HAVE_VK
#include <dstrans_vk_device.hpp>
#endif

namespace dstrans::cli {

struct gpu {
  std::string device, driver;  // what it runs on, as the driver names it
#ifdef DSTRANS_HAVE_GL
  std::unique_ptr<gl::headless_context> gl;  // current on this thread while it lives
#endif
#ifdef DSTRANS_HAVE_VK
  std::unique_ptr<vk::headless_device> vk_instance;
  std::unique_ptr<vk::device> vk;  // declared after the instance, so destroyed before it
#endif
};

// A GPU for `backend` ("gl" or "vk") on `device` (headless_device::create and headless_context::create say
// how it is chosen: "" the default, a number, or part of its name); a failure says why there is none
// ("no OpenGL: ...", or that the build left the backend out).
result<std::unique_ptr<gpu>> open_gpu(const std::string& backend, const std::string& device = "");
// The devices each backend of the build can run on, as `--device list` prints them.
std::string device_list();

}  // namespace dstrans::cli

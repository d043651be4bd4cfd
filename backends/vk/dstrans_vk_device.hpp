// A headless Vulkan 1.3 instance and device (Mesa lavapipe without a display, or any driver), with the
// Khronos validation layer when asked. For tools and tests: an engine has its own device and passes it
// to dstrans::vk::device::create through dstrans::vk::context instead.
//
//   auto hd = dstrans::vk::headless_device::create(true);     // with validation
//   if (!hd) { std::fprintf(stderr, "%s\n", hd.error().c_str()); return 1; }   // no device, no layer, ...
//   auto dev = dstrans::vk::device::create((*hd)->ctx());
//   ...
//   for (auto& m : (*hd)->validation_messages()) std::puts(m.c_str());
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "dstrans_vk.hpp"

namespace dstrans::vk {

class headless_device {
 public:
  // A device with one graphics-and-compute queue and dynamic rendering, or why there is none.
  static result<std::unique_ptr<headless_device>> create(bool validation);
  ~headless_device();
  headless_device(const headless_device&) = delete;
  headless_device& operator=(const headless_device&) = delete;

  const context& ctx() const { return ctx_; }
  // VkPhysicalDeviceProperties::deviceName, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  std::string name() const;
  // The validation layer's warnings and errors since the last call.
  std::vector<std::string> validation_messages();

 private:
  headless_device() = default;
  context ctx_;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  std::vector<std::string> messages_;
};

}  // namespace dstrans::vk

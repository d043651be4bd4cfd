// A headless Vulkan 1.3 instance and device (Mesa lavapipe without a display, or any driver), with the
// Khronos validation layer when asked. For tools and tests: an engine has its own device and passes it
// to dstrans::vk::device::create through dstrans::vk::context instead.
//
//   auto hd = dstrans::vk::headless_device::create(true);     // with validation, on the first device that serves
//   if (!hd) { std::fprintf(stderr, "%s\n", hd.error().c_str()); return 1; }   // no device, no layer, ...
//   auto on_gpu = dstrans::vk::headless_device::create(false, "NVIDIA");   // or "1": by name or index
//   for (const std::string& d : *dstrans::vk::headless_device::devices()) std::puts(d.c_str());
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
  // A device with one graphics-and-compute queue and dynamic rendering, or why there is none. `device`
  // chooses the physical device: "" the first that serves, a number its index in devices(), anything
  // else the first whose name contains it.
  static result<std::unique_ptr<headless_device>> create(bool validation, const std::string& device = "");
  // The physical devices in Vulkan's order, one line each: "0: llvmpipe (LLVM 15.0.6, 256 bits), cpu, llvmpipe
  // Mesa 22.3.6 (LLVM 15.0.6)".
  static result<std::vector<std::string>> devices();
  ~headless_device();
  headless_device(const headless_device&) = delete;
  headless_device& operator=(const headless_device&) = delete;

  const context& ctx() const { return ctx_; }
  // VkPhysicalDeviceProperties::deviceName, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  std::string name() const;
  // The driver's name and version (VkPhysicalDeviceDriverProperties), e.g. "llvmpipe Mesa 22.3.6 (LLVM 15.0.6)".
  std::string driver() const;
  // The validation layer's warnings and errors since the last call.
  std::vector<std::string> validation_messages();

 private:
  headless_device() = default;
  context ctx_;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  std::vector<std::string> messages_;
};

}  // namespace dstrans::vk

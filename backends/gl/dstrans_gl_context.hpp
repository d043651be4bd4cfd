// A headless OpenGL 4.5 core context on EGL's surfaceless platform (Mesa llvmpipe without a display, or
// any EGL driver with EGL_MESA_platform_surfaceless), or on one of EGL's devices (EGL_EXT_platform_device:
// a GPU's driver without a display). For tools and tests: an engine has its own context and never needs
// this file. One at a time per process: destroying one terminates the EGL display.
//
//   auto ctx = dstrans::gl::headless_context::create();
//   if (!ctx) { std::fprintf(stderr, "%s\n", ctx.error().c_str()); return 1; }   // no EGL display, ...
//   // GL calls work on this thread now; (*ctx)->debug_messages() lists what KHR_debug reported.
//   auto on_gpu = dstrans::gl::headless_context::create("NVIDIA");   // or "1": an EGL device by name or index
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <dstrans/result.hpp>

namespace dstrans::gl {

class headless_context {
 public:
  // A current GL 4.5 core debug context on this thread, or why there is none. `device` "": Mesa's
  // surfaceless platform, else EGL's first device; a number: that EGL device; anything else: the first EGL
  // device whose GL_RENDERER contains it.
  static result<std::unique_ptr<headless_context>> create(const std::string& device = "");
  // EGL's devices, one line each with what a context on it reports: "0: llvmpipe (LLVM 15.0.6, 256 bits),
  // 4.5 (Core Profile) Mesa 22.3.6"; empty without EGL_EXT_device_enumeration.
  static result<std::vector<std::string>> devices();
  ~headless_context();
  headless_context(const headless_context&) = delete;
  headless_context& operator=(const headless_context&) = delete;

  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  std::string renderer() const;
  // GL_VERSION, which names the driver: "4.5 (Core Profile) Mesa 22.3.6".
  std::string version() const;
  // The errors and warnings KHR_debug reported since the last call (notifications are left out).
  std::vector<std::string> debug_messages();

 private:
  headless_context() = default;
  // A context on `display` (an EGLDisplay, not yet initialised), or why there is none there (`why_none`
  // where the display itself is missing).
  static result<std::unique_ptr<headless_context>> on(void* display, const std::string& why_none);
  struct impl;
  std::unique_ptr<impl> impl_;
};

}  // namespace dstrans::gl

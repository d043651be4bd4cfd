// A headless OpenGL 4.5 core context on EGL's surfaceless platform (Mesa llvmpipe without a display, or
// any EGL driver with EGL_MESA_platform_surfaceless). For tools and tests: an engine has its own context
// and never needs this file. One at a time per process: destroying one terminates the EGL display.
//
//   auto ctx = dstrans::gl::headless_context::create();
//   if (!ctx) { std::fprintf(stderr, "%s\n", ctx.error().c_str()); return 1; }   // no EGL display, ...
//   // GL calls work on this thread now; (*ctx)->debug_messages() lists what KHR_debug reported.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <dstrans/result.hpp>

namespace dstrans::gl {

class headless_context {
 public:
  // A current GL 4.5 core debug context on this thread, or why there is none.
  static result<std::unique_ptr<headless_context>> create();
  ~headless_context();
  headless_context(const headless_context&) = delete;
  headless_context& operator=(const headless_context&) = delete;

  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  std::string renderer() const;
  // The errors and warnings KHR_debug reported since the last call (notifications are left out).
  std::vector<std::string> debug_messages();

 private:
  headless_context() = default;
  struct impl;
  std::unique_ptr<impl> impl_;
};

}  // namespace dstrans::gl

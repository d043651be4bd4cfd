// Implements dstrans_gl_context.hpp with EGL 1.5, EGL_MESA_platform_surfaceless and EGL_EXT_platform_device.
#include "dstrans_gl_context.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "dstrans_gl.hpp"

namespace dstrans::gl {

struct headless_context::impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  std::vector<std::string> messages;
};

namespace {
void APIENTRY on_debug_message(GLenum, GLenum type, GLuint, GLenum severity, GLsizei, const GLchar* message,
                                 const void* user) {
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  auto* messages = static_cast<std::vector<std::string>*>(const_cast<void*>(user));
  messages->push_back(std::string(type == GL_DEBUG_TYPE_ERROR ? "GL error: " : "GL: ") + message);
}
// EGL_EXT_device_enumeration's devices; none where EGL has not that extension.
std::vector<EGLDeviceEXT> egl_devices() {
  auto query = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  EGLint n = 0;
  if (!query || !query(0, nullptr, &n) || n <= 0) return {};
  std::vector<EGLDeviceEXT> devices(std::size_t(n), EGL_NO_DEVICE_EXT);
  if (!query(n, devices.data(), &n)) return {};
  devices.resize(std::size_t(n));
  return devices;
}

PFNEGLGETPLATFORMDISPLAYEXTPROC platform_display() {
  return reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
}
}  // namespace

result<std::unique_ptr<headless_context>> headless_context::create(const std::string& device) {
  const PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display = platform_display();
  if (!get_platform_display) return failure{"EGL has no eglGetPlatformDisplayEXT: no EGL driver is installed"};
  const std::vector<EGLDeviceEXT> all = egl_devices();
  if (device.empty()) {
    auto ctx = on(get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
                  "the surfaceless platform is unavailable (install libegl-mesa0)");
    if (ctx || all.empty()) return ctx;
    // A driver without Mesa's platform (NVIDIA's): its first device.
    return on(get_platform_display(EGL_PLATFORM_DEVICE_EXT, all[0], nullptr),
              "the surfaceless platform is unavailable and EGL device 0 has none");
  }
  const bool index = device.find_first_not_of("0123456789") == std::string::npos;
  std::string listed;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (index && device != std::to_string(i)) continue;
    auto ctx = on(get_platform_display(EGL_PLATFORM_DEVICE_EXT, all[i], nullptr), "the device has none");
    if (ctx && (index || (*ctx)->renderer().find(device) != std::string::npos)) return ctx;
    if (index) return failure{"EGL device " + device + ": " + ctx.error()};
    listed += "\n  " + std::to_string(i) + ": " + (ctx ? (*ctx)->renderer() : ctx.error());
  }
  if (index) return failure{"no EGL device number '" + device + "': EGL has " + std::to_string(all.size())};
  return failure{"no EGL device named '" + device + "'; the devices are:" + (listed.empty() ? std::string(" none") : listed)};
}

result<std::vector<std::string>> headless_context::devices() {
  if (!platform_display()) return failure{"EGL has no eglGetPlatformDisplayEXT: no EGL driver is installed"};
  std::vector<std::string> out;
  for (std::size_t i = 0; i < egl_devices().size(); ++i) {
    auto ctx = create(std::to_string(i));
    out.push_back(std::to_string(i) + ": " + (ctx ? (*ctx)->renderer() + ", " + (*ctx)->version() : ctx.error()));
  }
  return out;
}

result<std::unique_ptr<headless_context>> headless_context::on(void* native, const std::string& why_none) {
  const EGLDisplay display = native;
  EGLint major = 0, minor = 0;
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) return failure{"no EGL display: " + why_none};
  std::unique_ptr<headless_context> ctx(new headless_context);
  ctx->impl_ = std::make_unique<impl>();
  ctx->impl_->display = display;
  if (!eglBindAPI(EGL_OPENGL_API)) return failure{"EGL cannot bind the desktop OpenGL API"};
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                               EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE, EGL_NONE};
  ctx->impl_->context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (ctx->impl_->context == EGL_NO_CONTEXT) return failure{"EGL cannot create an OpenGL 4.5 core context"};
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx->impl_->context))
    return failure{"EGL cannot make the context current without a surface"};
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(on_debug_message, &ctx->impl_->messages);
  return ctx;
}

headless_context::~headless_context() {
  if (!impl_) return;
  if (impl_->context != EGL_NO_CONTEXT) {
    glDebugMessageCallback(nullptr, nullptr);
    eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(impl_->display, impl_->context);
  }
  eglTerminate(impl_->display);
}

std::string headless_context::renderer() const {
  return reinterpret_cast<const char*>(glGetString(GL_RENDERER));
}

std::string headless_context::version() const { return reinterpret_cast<const char*>(glGetString(GL_VERSION)); }

std::vector<std::string> headless_context::debug_messages() {
  std::vector<std::string> out;
  out.swap(impl_->messages);
  return out;
}

}  // namespace dstrans::gl

// Implements dstrans_gl_context.hpp with EGL 1.5 and EGL_MESA_platform_surfaceless.
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
}  // namespace

result<std::unique_ptr<headless_context>> headless_context::create() {
  auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_platform_display) return failure{"EGL has no eglGetPlatformDisplayEXT: no EGL driver is installed"};
  EGLDisplay display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  EGLint major = 0, minor = 0;
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor))
    return failure{"no EGL display: the surfaceless platform is unavailable (install libegl-mesa0)"};
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

std::vector<std::string> headless_context::debug_messages() {
  std::vector<std::string> out;
  out.swap(impl_->messages);
  return out;
}

}  // namespace dstrans::gl

// The dstrans viewer: any scene file in a GLFW window, drawn by the library's OpenGL frame
// (dstrans::gl::renderer), with an orbit camera, keys for every effect and technique, and the GPU time of each
// pass in the window title.
//
//   viewer examples/scenes/pane.json                 # until the window closes
//   viewer examples/scenes/pane.json --frames 3      # three frames, the last title on stdout, then exit
//   viewer examples/scenes/pane.json --frames 1 --out window.png   # and what the window showed
//   viewer examples/scenes/pane.json --shaders shaders/glsl   # pass shaders read from a folder (hot reload)
//
// Mouse: drag to orbit, scroll to zoom. Keys: 1-4 technique (interlaced, peeling, forward, forward with
// depth); S shadows (off, opaque, transparent); R refraction on/off; T transmittance (thesis, physical);
// F the full pipeline (every effect planned, whether the scene calls for it or not); L reloads the pass
// shaders (from --shaders DIR; the embedded ones otherwise); Esc quits.
// One renderer draws every frame; a key that changes the plan makes a new one (reading the shaders again),
// and orbiting only moves the camera.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>
#include <GLFW/glfw3.h>

#include "../example_io.hpp"

#define STB_IMAGE_WRITE_IMPLEMENTATION  // stb_image_write.h's definitions, here once
#include <stb/stb_image_write.h>

#include <dstrans_gl_frame.hpp>
#include <scene_json.hpp>

namespace {

using namespace dstrans;

const char* const usage =
    "usage: viewer <scene.json|.gltf|.glb> [--frames N [--out window.png]] [--width W] [--height H] [--shaders DIR]\n";

// What the keys change; a change asks for a new renderer.
struct settings {
  render::options o;
  bool changed = false;
};

// An orbit around the scene camera's target.
struct orbit {
  glm::vec3 target{0.0f};
  float distance = 5.0f, yaw = 0.0f, pitch = 0.3f;
  void from(const camera& c) {
    target = c.target;
    const glm::vec3 d = c.position - c.target;
    distance = glm::length(d);
    yaw = std::atan2(d.x, d.z);
    pitch = std::asin(glm::clamp(d.y / distance, -1.0f, 1.0f));
  }
  void place(camera& c) const {
    c.target = target;
    c.position = target + distance * glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
  }
};

struct viewer_state {
  settings now;
  orbit eye;
  bool dragging = false;
  double last_x = 0.0, last_y = 0.0;
};


void on_key(GLFWwindow* w, int key, int, int action, int) {
  if (action != GLFW_PRESS) return;
  auto* st = static_cast<viewer_state*>(glfwGetWindowUserPointer(w));
  render::options& o = st->now.o;
  switch (key) {
    case GLFW_KEY_1: o.method = render::technique::interlaced; break;
    case GLFW_KEY_2: o.method = render::technique::peeling; break;
    case GLFW_KEY_3: o.method = render::technique::forward; break;
    case GLFW_KEY_4: o.method = render::technique::forward_depth; break;
    case GLFW_KEY_S: o.shadows = render::shadow_mode((int(o.shadows) + 1) % 3); break;
    case GLFW_KEY_R: o.refraction = o.refraction > 0.0f ? 0.0f : 8.0f; break;
    case GLFW_KEY_T: o.physical_transmittance = !o.physical_transmittance; break;
    case GLFW_KEY_F: o.force = o.force == effects{} ? effects::all() : effects{}; break;
    case GLFW_KEY_L: break;  // the rebuild reads the shaders again
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(w, GLFW_TRUE); return;
    default: return;
  }
  st->now.changed = true;
}

void on_button(GLFWwindow* w, int button, int action, int) {
  auto* st = static_cast<viewer_state*>(glfwGetWindowUserPointer(w));
  if (button != GLFW_MOUSE_BUTTON_LEFT) return;
  st->dragging = action == GLFW_PRESS;
  glfwGetCursorPos(w, &st->last_x, &st->last_y);
}

void on_move(GLFWwindow* w, double x, double y) {
  auto* st = static_cast<viewer_state*>(glfwGetWindowUserPointer(w));
  if (!st->dragging) return;
  st->eye.yaw -= float(x - st->last_x) * 0.01f;
  st->eye.pitch = glm::clamp(st->eye.pitch + float(y - st->last_y) * 0.01f, -1.5f, 1.5f);
  st->last_x = x;
  st->last_y = y;
}

void on_scroll(GLFWwindow* w, double, double dy) {
  auto* st = static_cast<viewer_state*>(glfwGetWindowUserPointer(w));
  st->eye.distance = glm::max(0.2f, st->eye.distance * std::pow(0.9f, float(dy)));
}

}  // namespace

int main(int argc, char** argv) {
  std::string file, out, shader_dir;
  int frames = 0, width = 960, height = 540;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool valued = a == "--out" || a == "--frames" || a == "--width" || a == "--height" || a == "--shaders";
    if (a == "--help" || a == "-h") {
      std::fputs(usage, stdout);
      return 0;
    }
    if (valued && i + 1 >= argc) {
      std::fprintf(stderr, "viewer: %s needs a value\n%s", a.c_str(), usage);
      return 2;
    }
    if (a == "--out" || a == "--shaders") {
      (a == "--out" ? out : shader_dir) = argv[++i];
    } else if (valued) {
      // The renderer's largest image, as dstrans render's (a window past the display's limits is an X error).
      int& v = a == "--frames" ? frames : a == "--width" ? width : height;
      if (!example::whole_number(a.c_str(), argv[++i], 1, a == "--frames" ? 100000 : 8192, v)) return 2;
    } else if (file.empty() && a.rfind("-", 0) != 0) {
      file = a;
    } else {
      std::fprintf(stderr, "viewer: %s '%s'\n%s", file.empty() ? "unknown argument" : "one scene only, not also", a.c_str(), usage);
      return 2;
    }
  }
  if (file.empty() || (!out.empty() && frames == 0)) {
    std::fprintf(stderr, "viewer: %s\n%s", file.empty() ? "which scene?" : "--out needs --frames N (the frame to keep)", usage);
    return 2;
  }
  const auto s = load_scene(file);
  if (!s) {
    std::fprintf(stderr, "viewer: %s\n", s.error().c_str());
    return 1;
  }
  if (!glfwInit()) {
    std::fprintf(stderr, "viewer: GLFW cannot start (no display?)\n");
    return 1;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
  GLFWwindow* window = glfwCreateWindow(width, height, "dstrans viewer", nullptr, nullptr);
  if (!window) {
    std::fprintf(stderr, "viewer: no OpenGL 4.5 core window here\n");
    glfwTerminate();
    return 1;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(0);
  GLint largest = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &largest);
  if (width > largest || height > largest) {
    std::fprintf(stderr, "viewer: %dx%d is larger than this GL's largest image (%d)\n", width, height, int(largest));
    glfwTerminate();
    return 1;
  }

  viewer_state st;
  st.now.o.width = width;
  st.now.o.height = height;
  st.now.o.shadow_size = 1024;
  st.eye.from(s->view);
  glfwSetWindowUserPointer(window, &st);
  glfwSetKeyCallback(window, on_key);
  glfwSetMouseButtonCallback(window, on_button);
  glfwSetCursorPosCallback(window, on_move);
  glfwSetScrollCallback(window, on_scroll);

  int drawn = 0;
  bool failed = false;  // a window picture that could not be written
  std::string title;
  // The final image's row 0 is its top; the window's is its bottom.
  auto show = [&](const gl::renderer& r) {
    glBlitNamedFramebuffer(r.output().framebuffer, 0, 0, 0, width, height, 0, height, width, 0, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    if (!out.empty() && drawn + 1 == frames) {
      // What the window shows, read back before the swap.
      std::vector<unsigned char> pixels(std::size_t(width) * std::size_t(height) * 4);
      glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
      glReadBuffer(GL_BACK);
      glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
      std::string error;
      if (!example::write_png(out, width, height, pixels.data(), true, error)) {
        std::fprintf(stderr, "viewer: %s\n", error.c_str());
        failed = true;
      }
    }
    glfwSwapBuffers(window);
    const frame_times times = r.times();
    std::string passes;
    for (const auto& [name, ms] : times.pass_ms) {
      char part[64];
      std::snprintf(part, sizeof part, "%s%s %.1f", passes.empty() ? "" : ", ", name.c_str(), ms);
      passes += part;
    }
    const render::options& o = st.now.o;
    char head[256];
    std::snprintf(head, sizeof head, "dstrans viewer: %s, shadows %s, refraction %s, %s%s: %.1f ms (", render::technique_name(o.method),
                  render::shadow_name(o.shadows), o.refraction > 0.0f ? "on" : "off",
                  o.physical_transmittance ? "physical" : "thesis", o.force == effects{} ? "" : ", full pipeline", times.frame_ms);
    title = head + passes + ")";
    glfwSetWindowTitle(window, title.c_str());
    ++drawn;
  };
  const gl::scene_geometry meshes(*s);
  std::unique_ptr<gl::renderer> r;
  camera view = s->view;
  while (!glfwWindowShouldClose(window) && (frames == 0 || drawn < frames)) {
    if (!r || st.now.changed) {
      st.now.changed = false;
      r.reset();
      const pass_shaders shaders = shader_dir.empty() ? pass_shaders() : pass_shaders(shader_dir);
      auto made = gl::renderer::create(*s, st.now.o, shaders);
      if (!made) {
        std::fprintf(stderr, "viewer: %s\n", made.error().c_str());
        glfwDestroyWindow(window);
        glfwTerminate();
        return 1;
      }
      r = std::move(*made);
    }
    st.eye.place(view);
    r->render(view, [&](const scheduled_pass& pass) { meshes(pass); });
    show(*r);
    glfwPollEvents();
  }
  std::printf("%s\n", title.c_str());
  glfwDestroyWindow(window);
  glfwTerminate();
  return failed ? 1 : 0;
}

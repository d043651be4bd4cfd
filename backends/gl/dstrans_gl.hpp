// dstrans on OpenGL 4.5 core: the part an engine copies unmodified (dstrans_gl.{hpp,cpp}).
//
// Implements, for the engine's current context:
//   - render targets and a framebuffer from a layout (make_targets), read back as bytes (read_texels);
//   - programs from generated and hand-written GLSL, with errors as "file:line: message" (make_program);
//   - meshes (make_mesh) and the full-screen triangle (draw_fullscreen);
//   - GPU timers (timer), KHR_debug labels and groups (label, debug_group);
//   - state_guard, which saves and restores the GL state dstrans's passes touch;
//   - formula_runner, which evaluates a shared formula over many inputs in a compute shader.
// It never creates a context and never loads GL: by default it includes <GL/glcorearb.h> with prototypes
// (link libOpenGL); an engine with its own loader defines DSTRANS_GL_INCLUDE as that loader's header.
//
//   auto gbuf = dstrans::gl::make_targets(dstrans::describe<dstrans::thesis_gbuffer>(), w, h, "gbuffer", true);
//   auto prog = dstrans::gl::make_program(vs, fs, "gbuffer pass");
//   { dstrans::gl::state_guard keep; dstrans::gl::debug_group g("gbuffer pass"); /* draw */ }
#pragma once

#ifdef DSTRANS_GL_INCLUDE
#include DSTRANS_GL_INCLUDE
#else
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>
#endif

#include <map>
#include <string>
#include <vector>

#include <dstrans/formula.hpp>
#include <dstrans/frame/slots.hpp>
#include <dstrans/glsl.hpp>
#include <dstrans/layout.hpp>
#include <dstrans/light_mesh.hpp>
#include <dstrans/material_textures.hpp>
#include <dstrans/result.hpp>

namespace dstrans::gl {

// The textures of one layout's targets, an optional 32-bit float depth texture, and the framebuffer that
// draws into them (draw buffer i = target i).
struct targets {
  GLuint framebuffer = 0;
  std::vector<GLuint> textures;
  std::vector<format> formats;
  GLuint depth = 0;
  int width = 0, height = 0;
};

// Targets for `layout` of `width` x `height`, labelled "<label> RT<i>"; a failure names what the
// device cannot hold (too many targets, a format it cannot render to, a zero or oversized extent).
result<targets> make_targets(const std::vector<target_desc>& layout, int width, int height, const std::string& label,
                             bool with_depth);
void destroy(targets& t);

// Draws into `t` from now on: binds its framebuffer, sets the viewport to its size, and sets
// glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE), the one convention dstrans shares with Vulkan.
void bind(const targets& t);

// The bytes of target `index`, row by row from the top of the image (dstrans draws with
// glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE), so row 0 is the image's top on GL as on Vulkan).
std::vector<texel> read_texels(const targets& t, int index);

// A linked program from a vertex and a fragment shader, or from a compute shader; failures carry the
// driver's log with positions mapped to the dstrans sources they came from.
result<GLuint> make_program(const glsl::source& vertex, const glsl::source& fragment, const std::string& label);
// The material textures `a` as a 2D array texture with its mip levels, filled, sampled repeating and
// trilinearly (the pass shaders wrap each texture as it says); a failure past the context's array limits.
// It touches the unpack state, which a state_guard restores.
result<GLuint> make_texture_array(const texture_array& a, const std::string& label);
result<GLuint> make_compute_program(const glsl::source& compute, const std::string& label);

// An indexed triangle mesh with positions at attribute 0.
struct mesh {
  GLuint vertex_array = 0, vertices = 0, indices = 0;
  GLsizei index_count = 0;
};
mesh make_mesh(const mesh_data& data, const std::string& label);
void destroy(mesh& m);
void draw(const mesh& m);

// Draws the full-screen triangle of glsl::fullscreen_vertex_shader() with `empty_vertex_array`, a
// vertex array with no attributes (core profiles draw nothing without one).
void draw_fullscreen(GLuint empty_vertex_array);

// GPU time between begin() and end(), from two GL_TIMESTAMP queries (llvmpipe's first GL_TIME_ELAPSED
// query in a context measures from the context's creation, so dstrans does not use that kind).
class timer {
 public:
  timer();
  ~timer();
  timer(const timer&) = delete;
  timer& operator=(const timer&) = delete;
  void begin();
  void end();
  // Waits for the result.
  double milliseconds() const;

 private:
  GLuint queries_[2] = {0, 0};
};

// Names a GL object for frame captures and debug messages (KHR_debug).
void label(GLenum identifier, GLuint name, const std::string& text);

// A named group of GL commands in frame captures, for the lifetime of the object.
class debug_group {
 public:
  explicit debug_group(const std::string& name);
  ~debug_group();
  debug_group(const debug_group&) = delete;
  debug_group& operator=(const debug_group&) = delete;
};

// Saves the GL state dstrans's passes change and restores it when destroyed, so dstrans can run inside
// an engine's frame: program, framebuffers, viewport, clip control, depth (test, write mask, function,
// clamp), blend (enable, functions, equations), cull (enable, face, winding), scissor test, vertex array,
// the generic value of vertex attribute 3 (as unsigned integers: the frame's light index), pixel pack and
// unpack alignment and buffers, the active texture unit, and every binding of the slot table
// (dstrans/frame/slots.hpp): the 2D, 3D, 2D-array and buffer textures of each texture and texel-buffer
// slot's units, each image slot's image unit, each block slot's buffer range, and the generic uniform and
// storage buffer bindings that binding a block changes. `storage_blocks` names further storage-buffer
// bindings the guarded work uses (the formula runner's two).
class state_guard {
 public:
  explicit state_guard(const std::vector<GLuint>& storage_blocks = {});
  ~state_guard();
  state_guard(const state_guard&) = delete;
  state_guard& operator=(const state_guard&) = delete;

 private:
  struct texture_unit {
    GLuint unit;
    GLint texture_2d, texture_3d, texture_2d_array, texture_buffer;
  };
  struct image_unit {
    GLuint unit;
    GLint name, level, layered, layer, access, format;
  };
  struct buffer_range {
    GLenum target;
    GLuint index;
    GLint name;
    GLint64 start, size;
  };
  GLint program_, draw_fb_, read_fb_, viewport_[4], clip_origin_, clip_depth_, depth_func_, blend_src_rgb_,
      blend_dst_rgb_, blend_src_a_, blend_dst_a_, blend_eq_rgb_, blend_eq_a_, cull_face_, front_face_,
      vertex_array_, active_texture_, pack_alignment_, unpack_alignment_, pack_buffer_, unpack_buffer_,
      uniform_buffer_, storage_buffer_;
  GLint unpack_layout_[5];  // GL_UNPACK_ROW_LENGTH, SKIP_ROWS, SKIP_PIXELS, IMAGE_HEIGHT, SKIP_IMAGES
  GLuint light_index_[4];
  GLboolean depth_test_, depth_mask_, blend_, cull_, scissor_, depth_clamp_;
  std::vector<texture_unit> textures_;
  std::vector<image_unit> images_;
  std::vector<buffer_range> buffers_;
};

// Evaluates shared formulas in compute shaders; programs are built on first use and kept.
class formula_runner {
 public:
  formula_runner() = default;
  ~formula_runner();
  formula_runner(const formula_runner&) = delete;
  formula_runner& operator=(const formula_runner&) = delete;
  // The packed results of `calls` calls of `f`, whose packed arguments follow each other in `args`.
  // Batches past the device's dispatch and storage-buffer limits run in several dispatches.
  result<words> run(const formula& f, const words& args, std::size_t calls);

 private:
  result<words> run_dispatch(GLuint program, const formula& f, const words& args, std::size_t calls);
  std::map<std::string, GLuint> programs_;
};

}  // namespace dstrans::gl

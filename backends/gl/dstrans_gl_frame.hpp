// dstrans on OpenGL 4.5: the whole frame, run on the engine's context (dstrans_gl_frame.{hpp,cpp}).
//
// Implements the frame executor: `renderer` compiles the programs and allocates the targets a frame needs
// once, then runs the frame's schedule (dstrans/frame/schedule.hpp) pass by pass, as often as asked, and
// calls the engine back in each geometry pass to draw its own meshes; `scene_geometry` is that callback for
// a dstrans::scene's meshes. Every GL binding and enable a frame touches is restored when it returns.
//
//   auto r = dstrans::gl::renderer::create(description, options);           // once
//   r->render(camera, [&](const dstrans::scheduled_pass& pass) {            // every frame
//     draw_my_meshes(pass.draws);   // the program, state, targets and blocks are bound
//   });
//   glBlitNamedFramebuffer(r->output().framebuffer, 0, ...);                // the image, row 0 at the top
//
// The geometry a pass draws (pass.draws) is either every surface but hair, the hair alone, or both; with
// options::opaque_shadows_depth_only, also the opaque surfaces alone or all but them (schedule.hpp). Its
// vertices give the world-space position at attribute 0 (vec3), the normal (hair: the tangent) at 1 (vec3)
// and the index of its material in the description's materials at 2 (uint); attribute 3 is the
// renderer's (leave it disabled in the engine's vertex arrays). Where the description's materials sample
// textures (effect::textures), attribute 4 gives the texture coordinates (vec2; disabled, they read the
// generic value, (0, 0) unless the engine set another).
#pragma once

#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <dstrans/frame/plan.hpp>
#include <dstrans/frame/schedule.hpp>
#include <dstrans/pass_shaders.hpp>
#include <dstrans/scene.hpp>

#include "dstrans_gl.hpp"

namespace dstrans::gl {

// The engine's geometry: called in every geometry pass of the schedule with that pass.
using draw_geometry = std::function<void(const scheduled_pass& pass)>;

// The frame's targets, for reading back or showing; zero or empty where the frame has none.
struct frame_targets {
  std::vector<gl::targets> gbuffers, light_buffers;  // one a layer (peeling: two; forward: none)
  gl::targets lit;                    // forward rendering's colour, normal (and depth)
  gl::targets composed;               // the frame before the post chain
  std::map<std::string, gl::targets> post;  // the post chain's, by name
  const gl::targets* output = nullptr;      // the image shown: the post chain's output, or `composed`
  gl::targets shadow_picture;         // the first shadowed light's shadow colour, copied in the first frame
  GLuint kbuffer_heads = 0;       // R32UI, each pixel's list head
  GLuint kbuffer_nodes = 0;       // a header (count, overflow, capacity) and the node pool, uvec4 each
  std::uint32_t kbuffer_capacity = 0;
  GLuint volume_atlas = 0;        // the light volumes' atlas, RGBA8 3D (0: no bake)
  glm::ivec3 volume_atlas_size{0};
};

class renderer {
 public:
  // Compiles every program and allocates every target a frame of `description` needs with `o`: its
  // materials, lights, particle systems and post chain, and, through its objects, the effects it calls
  // for and the bounds its shadow maps cover (the objects' meshes are drawn by the engine). The lights
  // and materials are uploaded here; the camera is given to each frame.
  static result<std::unique_ptr<renderer>> create(const scene& description, const render::options& o,
                                                  const pass_shaders& shaders = pass_shaders());
  ~renderer();
  renderer(const renderer&) = delete;
  renderer& operator=(const renderer&) = delete;

  // One frame seen from `view`, its geometry drawn by `draw`. The passes are queued without waiting.
  void render(const camera& view, const draw_geometry& draw);
  // Allocates the targets for a frame of `width` x `height` again; the programs stay.
  result<bool> resize(int width, int height);

  const frame_schedule& schedule() const;
  const render::frame_plan& plan() const;
  const render::options& options() const;
  const frame_targets& targets() const;
  const gl::targets& output() const { return *targets().output; }
  // The last frame's GPU times (waits for them).
  frame_times times() const;

 private:
  struct impl;
  explicit renderer(std::unique_ptr<impl> p);
  std::unique_ptr<impl> p_;
};

// A dstrans::scene's meshes as the engine geometry of `renderer`: one vertex array of world-space
// vertices, hair last (dstrans::flatten), with texture coordinates where some shape has them.
class scene_geometry {
 public:
  explicit scene_geometry(const scene& s);
  ~scene_geometry();
  scene_geometry(const scene_geometry&) = delete;
  scene_geometry& operator=(const scene_geometry&) = delete;
  // Draws what `pass` asks for, less the objects outside its clip volume, with the back faces of the
  // closed objects it may cull culled (frame/culling.hpp); the face culling state is left as it was.
  void operator()(const scheduled_pass& pass) const;

 private:
  GLuint vertex_array_ = 0, buffers_[5] = {0, 0, 0, 0, 0};  // positions, normals, materials, indices, texture coordinates
  std::size_t hair_first_ = 0, index_count_ = 0;
  std::vector<mesh_part> parts_;  // the objects, culled in each pass
};

}  // namespace dstrans::gl

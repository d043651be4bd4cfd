// dstrans on Vulkan: the whole frame, recorded into the engine's command buffer (dstrans_vk_frame.{hpp,cpp}).
//
// Implements the frame executor: `renderer` builds the pipelines, targets, buffers and descriptor sets a
// frame needs once, on the engine's device (dstrans::vk::device over the engine's dstrans::vk::context),
// and records the frame's schedule (dstrans/frame/schedule.hpp) into a command buffer the engine owns and
// submits, with a barrier before each pass derived from what it reads and writes and the passes before it
// wrote and read (in this frame and the last), and a GPU timestamp around each pass. It never submits.
// The engine draws its own meshes in the geometry passes through a callback; `scene_geometry` is that
// callback for a dstrans::scene's meshes.
//
//   auto r = dstrans::vk::renderer::create(dev, description, options);      // once
//   r->record(cmd, camera, [&](VkCommandBuffer cmd, const dstrans::scheduled_pass& pass) {
//     bind_and_draw_my_meshes(cmd, pass.draws);   // pipeline, descriptor sets and targets are bound
//   });                                           // then the engine submits cmd
//   r->output();                                  // the image, in SHADER_READ_ONLY_OPTIMAL once cmd has run
//
// Layouts: while the frame runs, each image is in the layout its pass needs (colour and depth attachment,
// shader read-only, transfer source or destination; the k-buffer's storage image in GENERAL), moved there by
// the barrier before the pass. After the frame every target is in SHADER_READ_ONLY_OPTIMAL (the storage
// image in GENERAL), its writes visible to fragment and compute shaders and to transfers: the engine samples
// or copies output() with no barrier of its own, and leaves it in that layout for the next frame.
//
// Frames in flight: each of create's `frames_in_flight` frames has its own camera block, particle quads,
// descriptor sets and timestamps, used again `frames_in_flight` records later; before that record, the
// engine waits for the submission of the frame that used them (as it does for its own per-frame objects).
// Targets are shared: the barriers order one frame's passes after the last frame's, so the engine submits
// the command buffers in the order they were recorded.
//
// The engine's device needs dynamic rendering and the features depthClamp (light volumes) and
// fragmentStoresAndAtomics (the k-buffer's lists).
//
// The geometry a pass draws (pass.draws) is every surface but hair, the hair alone, or both (with
// options::opaque_shadows_depth_only also the opaque surfaces alone or all but them: schedule.hpp), at vertex
// bindings and attributes `vertex_input` (by default three streams: binding 0 the world-space position
// (vec3) at location 0, binding 1 the normal (hair: the tangent, vec3) at 1, binding 2 the material index
// (uint) at 2). Binding 3 is the renderer's (a light pass's light index). Draw with firstInstance 0. Where
// the description's materials sample textures (effect::textures), location 4 takes the texture
// coordinates (vec2; streams(true) reads them from binding 4); a layout without location 4 reads (0, 0)
// from a binding of the renderer's own, after the engine's last.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <dstrans/frame/plan.hpp>
#include <dstrans/frame/schedule.hpp>
#include <dstrans/pass_shaders.hpp>
#include <dstrans/scene.hpp>

#include "dstrans_vk.hpp"

namespace dstrans::vk {

// The engine's geometry: called in every geometry pass of the schedule with the command buffer and the pass.
using draw_geometry = std::function<void(VkCommandBuffer cmd, const scheduled_pass& pass)>;

// How the engine's vertices reach locations 0 (position), 1 (normal), 2 (material) and 4 (texture coordinates).
struct vertex_input {
  std::vector<VkVertexInputBindingDescription> bindings;
  std::vector<VkVertexInputAttributeDescription> attributes;
  // Three streams: position, normal and material index at bindings 0, 1, 2; with `texture_coordinates`
  // a fourth at binding 4.
  static vertex_input streams(bool texture_coordinates = false);
};

// The frame's targets, for reading back or showing; empty where the frame has none.
struct frame_targets {
  std::vector<targets> gbuffers, light_buffers;  // one a layer (peeling: two; forward: none)
  targets lit;                     // forward rendering's colour, normal (and depth)
  targets composed;                // the frame before the post chain
  std::map<std::string, targets> post;  // the post chain's, by name
  const targets* output = nullptr;      // the image shown: the post chain's output, or `composed`
  buffer shadow_picture;           // the first shadowed light's shadow colour (RGBA8), copied in the first frame
  image kbuffer_heads;             // R32_UINT, each pixel's list head
  buffer kbuffer_nodes;            // a header (count, overflow, capacity) and the node pool, uvec4 each
  std::uint32_t kbuffer_capacity = 0;
  image volume_atlas;              // the light volumes' atlas, RGBA8 3D, SHADER_READ_ONLY_OPTIMAL after a frame (none: no bake)
  glm::ivec3 volume_atlas_size{0};
};

class renderer {
 public:
  // Everything a frame of `description` needs with `o` (its materials, lights, particle systems and post
  // chain; through its objects, the effects it calls for and the bounds its shadow maps cover).
  static result<std::unique_ptr<renderer>> create(device& dev, const scene& description, const render::options& o,
                                                  const pass_shaders& shaders = pass_shaders(),
                                                  const vertex_input& vertices = vertex_input::streams(), int frames_in_flight = 2);
  ~renderer();
  renderer(const renderer&) = delete;
  renderer& operator=(const renderer&) = delete;

  // Records one frame seen from `view` into `cmd` (begun, outside rendering), its geometry drawn by `draw`.
  void record(VkCommandBuffer cmd, const camera& view, const draw_geometry& draw);
  // Makes the targets for a frame of `width` x `height` again; the pipelines stay. No frame may be in flight.
  result<bool> resize(int width, int height);

  const frame_schedule& schedule() const;
  const render::frame_plan& plan() const;
  const render::options& options() const;
  const frame_targets& targets() const;
  const vk::targets& output() const { return *targets().output; }
  // The GPU times of the frame recorded last (its submission must have completed).
  frame_times times() const;

 private:
  struct impl;
  explicit renderer(std::unique_ptr<impl> p);
  std::unique_ptr<impl> p_;
};

// A dstrans::scene's meshes as the engine geometry of `renderer`: world-space vertex streams, hair last
// (dstrans::flatten), at vertex_input::streams()'s bindings, with texture coordinates where some shape has
// them (input() says which).
class scene_geometry {
 public:
  static result<std::unique_ptr<scene_geometry>> create(device& dev, const scene& s);
  ~scene_geometry();
  scene_geometry(const scene_geometry&) = delete;
  scene_geometry& operator=(const scene_geometry&) = delete;
  // Binds the streams and draws what `pass` asks for, less the objects outside its clip volume, with the
  // back faces of the closed objects it may cull culled (frame/culling.hpp) where the bound pipeline takes
  // its cull mode as dynamic state (pipeline_state::dynamic_cull) and the device can set it.
  void operator()(VkCommandBuffer cmd, const scheduled_pass& pass) const;
  // The vertex input of its streams, for renderer::create.
  vertex_input input() const;

 private:
  explicit scene_geometry(device& dev) : dev_(dev) {}
  device& dev_;
  buffer buffers_[5];  // positions, normals, materials, indices, texture coordinates (none without)
  std::size_t hair_first_ = 0, index_count_ = 0;
  std::vector<mesh_part> parts_;  // the objects, culled in each pass
};

}  // namespace dstrans::vk

// What the renderers upload for a scene (the blocks of dstrans/frame/blocks.hpp), and the per-frame
// options both backends share.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <dstrans/frame/blocks.hpp>
#include <dstrans/frame/schedule.hpp>
#include <dstrans/interlace.hpp>
#include <dstrans/light_volume.hpp>
#include <dstrans/light_mesh.hpp>
#include <dstrans/pipeline.hpp>
#include <dstrans/post.hpp>
#include <dstrans/result.hpp>
#include <dstrans/scene.hpp>

namespace dstrans::render {

enum class shadow_mode { off, opaque, transparent };

// interlaced: the thesis's single G-buffer with transparent rows; peeling: deferred depth peeling, two
// full G-buffers and light buffers (4.1.2); forward, forward_depth: multi-pass forward rendering with
// the same interlacing, refraction checked by de-interlaced alpha or by depth (4.1.3, 4.1.4).
enum class technique { interlaced, peeling, forward, forward_depth };
inline bool is_forward(technique t) { return t == technique::forward || t == technique::forward_depth; }

// The G-buffer's layout: Table 3.1's (16 bytes a pixel), or compact_gbuffer (8 bytes, depth read from the
// depth attachment; issue 12).
enum class gbuffer_layout { thesis, compact };
inline const char* layout_name(gbuffer_layout l) { return l == gbuffer_layout::thesis ? "thesis" : "compact"; }

// Which pixels of the interlaced G-buffer keep glass (interlace.hpp): the thesis's rows, columns, or the
// 2x2 checker of inferred lighting. Shadow maps keep the thesis's rows.
enum class predicate { rows, columns, checker };

struct options {
  technique method = technique::interlaced;
  predicate interlace = predicate::rows;
  gbuffer_layout layout = gbuffer_layout::thesis;
  // How the compose pass finds a pixel's other layer: the partner's sample (the thesis), or the edge-aware
  // reconstruction from the other layer's samples around it (issue 12, dst_reconstruct).
  bool reconstruct = false;
  int width = 320, height = 180;
  float refraction = 8.0f;      // strength in pixels; 0 turns refraction off
  // A fraction of the receiver's distance from the light, along the light's axis: the receiver is moved
  // that far towards the light before it is compared with the shadow map (in linear depth), which removes
  // self-shadowing ("acne") at the cost of light leaking under occluders that touch their receiver. A
  // fraction, so that a scene scaled uniformly keeps its shadows.
  float shadow_bias = 0.005f;
  int shadow_size = 512;
  shadow_mode shadows = shadow_mode::transparent;  // for spot lights that cast them
  // Light through glass: the thesis's min(I_L, C) (Eq. 3.2), or the physically based I_L C.
  bool physical_transmittance = false;
  int frames = 1;  // frames rendered with the same resources; times are their medians
  // Light buffers and the final image in RGBA32F instead of RGBA8: additive light does not saturate at 1
  // and a NaN or infinity stays visible instead of being stored as 0 (for checking a frame's numbers).
  bool float_targets = false;
  // The k-buffer (many_layers, TECHNIQUES.md S1): how many nearest fragments a pixel shades fully (1 to
  // 32), and how the rest are shaded: the forward reference (all in order, all shaded fully), deferred
  // (the tail cheaply), tailless (the tail's opacity only), cheap (everything cheaply), or weighted
  // blended OIT instead of lists (the peer).
  int kbuffer_k = 8;
  std::uint32_t kbuffer_nodes = 0;  // the node pool's size; 0: kbuffer_nodes_per_pixel a pixel
  enum class layers { forward, deferred, tailless, cheap, wboit } kbuffer_variant = layers::deferred;
  // Particle systems (light_volumes, TECHNIQUES.md S2): lit from light volumes of `volume_cells` cells a
  // side on S2's six or four axes or on fourteen (a user-supplied set: the six and the cube's eight
  // corners), or by the forward reference, which lights each fragment by every light.
  enum class particle_light { six_axes, four_axes, fourteen_axes, forward } particles = particle_light::six_axes;
  int volume_cells = 16;
  // Every light drawn as a full-screen triangle instead of its volume mesh: the same light in every pixel
  // the mesh covers, for checking the meshes (attenuation and falloff leave the rest at zero).
  bool fullscreen_lights = false;
  // Effects planned even where the scene or the other options leave them nothing to do (the full
  // pipeline, for comparisons): refraction of strength 0, say, runs its code and moves no sample.
  effects force;
};

// What a frame of `s` with options `o` consists of, derived once for both backends from the effects the
// scene calls for (dstrans::scene_features), less those the options turn off, plus options::force.
struct frame_plan {
  effects on;
  pipeline_plan pipeline;  // the passes and targets of `on` (dstrans plan prints it)
  shadow_mode shadows;     // the shadow map: off, opaque (depth), transparent (depth and colour)
  std::vector<shadow_mode> lookups;  // per light: no shadow, the plain lookup, or Eq. 3.1's
  bool forward, forward_depth, peeling;
  int layers;              // G-buffers (and light buffers): 0 forward, 2 peeling, 1 interlaced
  post_plan post;          // the scene's post-processing chain (deferred techniques only; in pipeline too)
  bool uses(shadow_mode lookup) const {
    for (shadow_mode m : lookups)
      if (m == lookup) return true;
    return false;
  }
};
frame_plan plan_of(const scene& s, const options& o);
// Whether the options' images (the frame and the shadow map) fit a device whose images and viewports are
// at most `largest` texels a side: checked by both renderers before they allocate anything.
result<bool> fits_device(const options& o, int largest);
// The light whose shadow map the hair reads (Eq. 1): the last one drawn, as the maps share targets; -1: none.
int hair_shadow_light(const frame_plan& p);
// The names the command line, the benchmark and the viewer give techniques, shadows and k-buffer variants.
inline const char* technique_name(technique t) {
  switch (t) {
    case technique::interlaced: return "interlaced";
    case technique::peeling: return "peeling";
    case technique::forward: return "forward";
    case technique::forward_depth: return "forward-depth";
  }
  return "?";
}
inline const char* predicate_name(predicate p) {
  return p == predicate::rows ? "rows" : p == predicate::columns ? "columns" : "checker";
}
inline const char* shadow_name(shadow_mode m) {
  return m == shadow_mode::off ? "off" : m == shadow_mode::opaque ? "opaque" : "transparent";
}
inline const char* layers_name(options::layers v) {
  switch (v) {
    case options::layers::forward: return "forward";
    case options::layers::deferred: return "deferred";
    case options::layers::tailless: return "tailless";
    case options::layers::cheap: return "cheap";
    case options::layers::wboit: return "wboit";
  }
  return "?";
}

inline const char* particle_light_name(options::particle_light p) {
  switch (p) {
    case options::particle_light::six_axes: return "six-axes";
    case options::particle_light::four_axes: return "four-axes";
    case options::particle_light::fourteen_axes: return "fourteen-axes";
    case options::particle_light::forward: return "forward";
  }
  return "?";
}

constexpr shadow_mode all_lookups[] = {shadow_mode::off, shadow_mode::opaque, shadow_mode::transparent};
// How programs and pipelines of a lookup are labelled: "", " opaque shadows", " transparent shadows".
inline const char* lookup_label(shadow_mode m) {
  return m == shadow_mode::off ? "" : m == shadow_mode::opaque ? " opaque shadows" : " transparent shadows";
}

// The blocks of dstrans/frame/blocks.hpp, as the renderers fill them.
using frame_block = shader::dst_frame_data;
using material_block = shader::dst_material_data;
using light_block = shader::dst_light_data;

// The camera's frame block for an image of `o.width` x `o.height`.
frame_block camera_frame(const scene& s, const options& o);
// The same for camera `c` (a viewer's, moving from frame to frame).
frame_block camera_frame(const camera& c, glm::vec3 ambient, const options& o);
// The same, seen from spot light `l` of light_blocks (its shadow map's view and projection).
frame_block light_frame(const scene& s, const light_block& l, const options& o);
std::vector<material_block> material_blocks(const scene& s);
std::vector<light_block> light_blocks(const scene& s);
// Light volumes: the basis the options pick, the atlas of the scene's particle systems (a region of
// options::volume_cells cells a side over each system's bounds), and each system's region as the particle
// pass reads it.
basis particle_basis(const options& o);
volume_atlas particle_atlas(const scene& s, const options& o);
struct particle_region {
  glm::vec4 origin_material;  // the region's first cell corner; w: the system's material
  glm::vec4 scale_slab;       // a cell's size; w: the atlas's slab height
  glm::vec4 offset;           // the region's first texel
  glm::vec4 dims;             // its cells per axis
};
std::vector<particle_region> particle_regions(const scene& s, const volume_atlas& a);
// What a frame does for particle systems (both backends): whether it draws them (deferred techniques),
// by the forward reference or from baked volumes; the atlas; the lights as the bake reads them (from
// their light blocks, their index in s.lights in cos_inner.y for the shadow hook): the shadowed ones, each
// baked in its own dispatch (in light order, which is also the order of the reference's shadow-map
// layers), and the rest, baked together.
struct particle_plan {
  bool on = false, reference = false, baking = false;
  shadow_mode shadows = shadow_mode::off;  // the maps the particle pass and the bake read: none without a shadowed light
  volume_atlas atlas;
  std::vector<volume_light> shadowed_lights, unshadowed_lights;
};
particle_plan particle_plan_of(const scene& s, const frame_plan& p, const options& o);

// The passes a frame of `s` runs, in the order both renderers run them (dstrans/frame/schedule.hpp): its
// resources are "scene" (the frame's input), the G-buffers, light buffers, the shadow map, the k-buffer,
// the light volumes' texels and atlas, the shadow maps' layers, and "frame" (the composed image), which
// the post chain reads; the frame's output is the post chain's.
frame_schedule schedule_of(const scene& s, const frame_plan& p, const options& o);

// The volume mesh a light is drawn with: none (full screen) for directional lights (and for every light
// with options::fullscreen_lights), a sphere or a cone otherwise. A volume mesh is drawn with its back
// faces, depth clamped and no depth test: every pixel whose view ray meets the convex mesh in front of
// the camera sees exactly one back face there, wherever the camera is (inside, outside, on the boundary),
// and with the depth clamped neither the near nor the far plane clips it away. (The thesis draws front
// faces when the camera is outside, which the near plane cuts off when it crosses the volume.)
enum class volume { fullscreen, sphere, cone };
volume volume_of(const light& l, const options& o);

}  // namespace dstrans::render

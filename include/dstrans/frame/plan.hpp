// What a frame of the reference pipeline is, API-neutrally: the options a frame is drawn with, the plan
// derived from a scene's effects (frame_plan, plan_of), the passes in order (schedule_of), and the blocks
// the passes read (dstrans/frame/blocks.hpp) as a scene fills them. Backends run it; an engine may read it.
//
//   dstrans::render::options o;                    // a technique, a size, shadows, ...
//   const dstrans::render::frame_plan p = dstrans::render::plan_of(scene, o);
//   for (const dstrans::scheduled_pass& pass : dstrans::render::schedule_of(scene, p, o).passes) ...
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "../gbuffer.hpp"
#include "../interlace.hpp"
#include "../layout.hpp"
#include "../light_mesh.hpp"
#include "../light_volume.hpp"
#include "../particles.hpp"
#include "../pipeline.hpp"
#include "../post.hpp"
#include "../result.hpp"
#include "../scene.hpp"
#include "../transparent_shadow.hpp"
#include "blocks.hpp"
#include "schedule.hpp"

namespace dstrans::render {

enum class shadow_mode { off, opaque, transparent };

// interlaced: the thesis's single G-buffer with transparent rows; peeling: deferred depth peeling, two
// full G-buffers and light buffers (4.1.2); forward, forward_depth: multi-pass forward rendering with
// the same interlacing, refraction checked by de-interlaced alpha or by depth (4.1.3, 4.1.4); reference:
// the exact reference, the opaque surfaces deferred and every transparent fragment (glass, hair, particles)
// shaded fully into per-pixel lists, sorted and blended in order, without refraction.
enum class technique { interlaced, peeling, forward, forward_depth, reference };
inline bool is_forward(technique t) { return t == technique::forward || t == technique::forward_depth; }

// The G-buffer's layout: Table 3.1's (16 bytes a pixel), or compact_gbuffer (8 bytes, depth read from the
// depth attachment).
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
  // reconstruction from the other layer's samples around it (dst_reconstruct).
  bool reconstruct = false;
  // Temporal interlacing (interlaced technique with glass): the rows (columns, checker squares) that keep glass
  // change places every frame, and the compose pass takes a pixel's other layer from the previous frame's
  // G-buffer where it lies on the pixel's ray now and is the layer missing there, else as `reconstruct` says.
  // The previous frame's G-buffer and light buffer are kept: they double the layer's bytes.
  bool temporal = false;
  int width = 320, height = 180;
  float refraction = 8.0f;      // strength in pixels; 0 turns refraction off
  // Rough glass (deferred techniques, with refraction): the compose pass blurs the refracted sample by the
  // glass's roughness, read back from its Phong exponent (refraction.hpp), at up to 15 samples a glass pixel.
  // Off by default: dstrans's own materials choose their exponent for the highlight alone.
  bool rough_refraction = false;
  // A fraction of the receiver's distance from the light, along the light's axis: the receiver is moved
  // that far towards the light before it is compared with the shadow map (in linear depth), which removes
  // self-shadowing ("acne") at the cost of light leaking under occluders that touch their receiver. A
  // fraction, so that a scene scaled uniformly keeps its shadows.
  float shadow_bias = 0.005f;
  // Soft shadows: each lookup averages Eq. 3.1 over this many texels a side around the receiver's (odd; 1:
  // the thesis's hard shadows), each texel with its own interlace partner, so that a glass texel is only
  // ever paired with the opaque one beside it. The receiver moves a texel along its normal for each ring.
  int shadow_filter = 1;
  int shadow_size = 512;
  shadow_mode shadows = shadow_mode::transparent;  // for the lights that cast them, of every kind
  // A transparent shadow map drawn in two passes a view: first the opaque surfaces (geometry_set::opaque),
  // their depth and the clear colour without their material (shadow.frag.glsl's DST_DEPTH_ONLY), then the
  // rest with the full shader (geometry_set::not_opaque), where a single pass runs the full shader for every
  // fragment. The same map for every lookup: Eq. 3.1 reads an opaque texel's alpha and depth, never its
  // colour. For draw callbacks that tell the two sets apart (scene_mesh::parts do).
  bool opaque_shadows_depth_only = false;
  // Light through glass: the thesis's min(I_L, C) (Eq. 3.2), or the physically based I_L C.
  bool physical_transmittance = false;
  int frames = 1;  // frames rendered with the same resources; times are their medians
  // Light buffers and the final image in RGBA32F instead of RGBA8: additive light does not saturate at 1
  // and a NaN or infinity stays visible instead of being stored as 0 (for checking a frame's numbers).
  bool float_targets = false;
  // The light buffer's specular in RGB (rgb_light_buffer, 8 bytes a pixel) instead of the thesis's white
  // (thesis_light_buffer, 4): a coloured light's highlight keeps its colour. Forward rendering follows it.
  bool rgb_specular = false;
  // The k-buffer (many_layers): how many nearest fragments a pixel shades fully (1 to
  // 32), and how the rest are shaded: the forward reference (all in order, all shaded fully), deferred
  // (the tail cheaply), tailless (the tail's opacity only), cheap (everything cheaply), or weighted
  // blended OIT instead of lists (the peer).
  int kbuffer_k = 8;
  std::uint32_t kbuffer_nodes = 0;  // the node pool's size; 0: kbuffer_nodes_per_pixel a pixel
  enum class layers { forward, deferred, tailless, cheap, wboit } kbuffer_variant = layers::deferred;
  // Particle systems (light_volumes): lit from light volumes of `volume_cells` cells a
  // side on S2's six or four axes or on fourteen (a user-supplied set: the six and the cube's eight
  // corners), from the light's moments, or by the forward reference, which lights each fragment by every light.
  enum class particle_light { six_axes, four_axes, fourteen_axes, moments, forward } particles = particle_light::six_axes;
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
  // A transparent map's opaque surfaces drawn first, by depth alone (options::opaque_shadows_depth_only).
  bool depth_only_shadows;
  std::vector<shadow_mode> lookups;  // per light: no shadow, the plain lookup, or Eq. 3.1's
  bool forward, forward_depth, peeling;
  bool exact;              // technique::reference
  // Per-pixel lists (the k-buffer's nodes, heads and tail targets): for hair, or in the exact reference for
  // every transparent fragment of a scene that has any.
  bool lists;
  // The shadow maps copied into the layers of an array as each is drawn, for the passes that light a
  // fragment by every light at once: the particles' forward reference, the exact reference.
  bool shadow_layers;
  bool temporal;           // temporal interlacing: a second G-buffer holds the previous frame's
  // Whether the shadow pass samples the materials' textures (render::textured_shadows, or forced). Where it
  // does not, it reads no texture coordinates: it is built for shadow_effects(), `on` less effect::textures.
  bool textured_shadows;
  int layers;              // G-buffers (and light buffers) a frame draws: 0 forward, 2 peeling, 1 interlaced
  // Hair and particles drawn around the glass (dstrans::around_glass, deferred techniques): the k-buffer's
  // resolve and the particle pass draw into glass_layer_targets before the compose pass, which lays what
  // lies behind a pixel's glass under it, refracted with the surface behind, and the rest over it.
  bool around_glass;
  post_plan post;          // the scene's post-processing chain (deferred techniques only; in pipeline too)
  // The G-buffers (and light buffers) kept: those drawn, and with temporal interlacing the previous frame's.
  int kept_layers() const { return temporal ? 2 : layers; }
  // The effects the shadow pass is built for.
  effects shadow_effects() const { return textured_shadows ? on : on.without(effect::textures); }
  bool uses(shadow_mode lookup) const {
    for (shadow_mode m : lookups)
      if (m == lookup) return true;
    return false;
  }
};
frame_plan plan_of(const scene& s, const options& o);
// Whether a frame with options `o` and effects `on` interlaces temporally (frame_plan::temporal).
bool temporal_interlacing(const options& o, effects on);
// Whether a texture can change a shadow of `s`: an object's material is textured and glass (its texels colour
// the light through it) or alpha-tested (they cut the occluder out). An opaque occluder's shadow is its
// depth, whatever its texels, so the shadow pass need not read them for it.
bool textured_shadows(const scene& s);
// Whether the compose pass of a frame with options `o` and effects `on` blurs refraction through rough glass
// (options::rough_refraction: the switch DST_ROUGH_REFRACTION).
bool rough_refraction(const options& o, effects on);
// Whether the options' images (the frame and the shadow map) fit a device whose images and viewports are
// at most `largest` texels a side: checked by both renderers before they allocate anything.
result<bool> fits_device(const options& o, int largest);
// Whether scene `s`'s materials fit a device whose buffer textures (GL) or texel buffers (Vulkan) hold at
// most `most_texels` texels: frame.glsl's dst_material reads a material block as RGBA32F texels, three.
result<bool> materials_fit(const scene& s, std::uint64_t most_texels);
// The light whose shadow map the hair reads (Eq. 1): the last one drawn, as the maps share targets; -1: none.
int hair_shadow_light(const frame_plan& p);
// The names the command line, the benchmark and the viewer give techniques, shadows and k-buffer variants.
inline const char* technique_name(technique t) {
  switch (t) {
    case technique::interlaced: return "interlaced";
    case technique::peeling: return "peeling";
    case technique::forward: return "forward";
    case technique::forward_depth: return "forward-depth";
    case technique::reference: return "reference";
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
    case options::particle_light::moments: return "moments";
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

// The camera's frame block for an image of `o.width` x `o.height`: a first frame, with no previous one.
frame_block camera_frame(const scene& s, const options& o);
// What temporal interlacing adds to a pixel before the interlace predicate in frame `index`: every other
// frame the rows (columns, checker squares) that keep glass change places.
glm::ivec2 interlace_phase(predicate p, std::uint64_t index);
// The camera block `f` as frame `index` (from 0) of a sequence drawn by plan `p` with the same targets,
// `previous` being frame index - 1's: the light whose shadow map hair reads under `p`, and with temporal
// interlacing that frame's interlace phase and the previous frame's matrices, with which the compose pass
// finds the second G-buffer's samples.
frame_block sequence_frame(frame_block f, const frame_block& previous, std::uint64_t index, const frame_plan& p,
                           const options& o);
// The same for scene `s` seen from camera `c` (a viewer's, moving from frame to frame).
frame_block camera_frame(const scene& s, const camera& c, const options& o);
// The same, seen from light `l` of light_blocks as its shadow map's view `view` (a point light's cube face
// 0-5, drawn into its tile; other maps have one view, 0) sees it.
frame_block light_frame(const scene& s, const light_block& l, const options& o, int view = 0);
// How many views light `l`'s shadow map is drawn from: six for a point light's cube, else one.
int shadow_views(const light_block& l);
// Whether frame `f` of sequence_frame is composed by the compose pass's still-camera variant
// (DST_STILL_CAMERA): temporal interlacing, and the previous frame was seen with the same view_proj.
bool still_camera(const frame_block& f);
std::vector<material_block> material_blocks(const scene& s);
std::vector<light_block> light_blocks(const scene& s);
// Light volumes: the model the options pick, the atlas of the scene's particle systems (a region of
// options::volume_cells cells a side over each system's bounds), and (particle_regions, after
// particle_plan) each system's region as the particle pass reads it.
volume_model particle_model(const options& o);
volume_atlas particle_atlas(const scene& s, const options& o);
struct particle_region {
  glm::vec4 origin_material;  // the region's first cell corner; w: the system's material
  glm::vec4 scale_slab;       // a cell's size; w: the atlas's slab height
  glm::vec4 offset_range;     // the region's first texel; w: its range
  glm::vec4 dims;             // its cells per axis
};
// What a frame does for particle systems (both backends): whether it draws them (deferred techniques),
// by the forward reference or from baked volumes; the atlas; the lights as the bake reads them (from
// their light blocks, their index in s.lights in cos_inner.y for the shadow hook): the shadowed ones, each
// baked in its own dispatch (in light order, which is also the order of the reference's shadow-map
// layers), and the rest, baked together.
struct particle_plan {
  bool on = false, reference = false, baking = false;
  shadow_mode shadows = shadow_mode::off;  // the maps the particle pass and the bake read: none without a shadowed light
  volume_atlas atlas;
  std::vector<float> ranges;  // a region each: volume_range over all the lights
  std::vector<volume_light> shadowed_lights, unshadowed_lights;
};
particle_plan particle_plan_of(const scene& s, const frame_plan& p, const options& o);
// The same from `lights`, the scene's light_blocks, where the caller has them (each light_blocks call
// walks every vertex of the scene for its bounds); `lights` of another length than s.lights is computed
// again.
particle_plan particle_plan_of(const scene& s, const frame_plan& p, const options& o, const std::vector<light_block>& lights);
std::vector<particle_region> particle_regions(const scene& s, const particle_plan& smoke);

// The passes a frame of `s` runs, in the order both renderers run them (dstrans/frame/schedule.hpp): its
// resources are "scene" (the frame's input), the G-buffers, light buffers, the shadow map, the k-buffer,
// the light volumes' atlas, the shadow maps' layers, and "frame" (the composed image), which
// the post chain reads; the frame's output is the post chain's.
frame_schedule schedule_of(const scene& s, const frame_plan& p, const options& o);
// The same from `lights`, the scene's light_blocks, where the caller has them (of another length than
// s.lights: computed again).
frame_schedule schedule_of(const scene& s, const frame_plan& p, const options& o, const std::vector<light_block>& lights);

// The volume mesh a light is drawn with: none (full screen) for directional lights (and for every light
// with options::fullscreen_lights), a sphere or a cone otherwise. A volume mesh is drawn with its back
// faces, depth clamped and no depth test: every pixel whose view ray meets the convex mesh in front of
// the camera sees exactly one back face there, wherever the camera is (inside, outside, on the boundary),
// and with the depth clamped neither the near nor the far plane clips it away. (The thesis draws front
// faces when the camera is outside, which the near plane cuts off when it crosses the volume.)
enum class volume { fullscreen, sphere, cone };
volume volume_of(const light& l, const options& o);

// The G-buffer layout's targets, and what a frame clears them to: empty pixels are opaque black at the
// far plane.
std::vector<target_desc> gbuffer_targets(gbuffer_layout l);
std::vector<glm::vec4> gbuffer_clears(gbuffer_layout l);

// The final image's target.
inline target_desc final_target_desc(bool float_targets) {
  return {float_targets ? format::rgba32f : format::rgba8, {"r", "g", "b", "a"}};
}

// Definitions.
namespace frame_detail {
// Cones wider than this are drawn as spheres: a cone's mesh grows without bound towards 90 degrees.
inline constexpr float widest_cone = 60.0f;

// A sphere around every object of the scene.
struct bounds {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
};
inline bounds scene_bounds(const scene& s) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const object& ob : s.objects)
    for (const glm::vec3& p : ob.geometry.positions) {
      const glm::vec3 w = glm::vec3(ob.transform * glm::vec4(p, 1.0f));
      lo = glm::min(lo, w);
      hi = glm::max(hi, w);
    }
  if (!(lo.x <= hi.x)) return {};
  return {(lo + hi) * 0.5f, glm::length(hi - lo) * 0.5f};
}

// The near and far planes of a spot light's shadow map: where the scene's bounds begin and end seen from
// the light, within its range. Derived from lengths of the scene alone, so that a scene scaled uniformly
// gets the same window depths (a constant floor on the near plane made shadows depend on the scale).
inline glm::vec2 shadow_planes(const bounds& b, const light& l) {
  const float d = glm::length(b.centre - l.position);
  const float far_plane = std::min(l.range, d + b.radius);
  return {std::clamp(d - b.radius, far_plane * 1e-3f, far_plane * 0.5f), far_plane};
}

inline glm::mat4 view_along(glm::vec3 eye, glm::vec3 direction) {
  const glm::vec3 up = std::fabs(glm::normalize(direction).y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::lookAtRH(eye, eye + direction, up);
}

inline glm::mat4 spot_view(const light& l) { return view_along(l.position, l.direction); }

// The view of cube face `face` from `eye`: the shared face view (dst_cube_face_view) of the offset from it.
inline glm::mat4 cube_face_view(glm::vec3 eye, int face) {
  glm::mat4 m(1.0f);
  for (int axis = 0; axis < 3; ++axis) {
    glm::vec3 e(0.0f);
    e[axis] = 1.0f;
    m[axis] = glm::vec4(shader::dst_cube_face_view(e, face), 0.0f);
  }
  return m * glm::translate(glm::mat4(1.0f), -eye);
}

// A directional light's shadow map: orthographic, along the light's direction, over the scene's bounding
// sphere (radius r) seen from 2 r before its centre, so its near and far planes are r and 3 r and a texel
// spans 2 r / size of the scene. An empty scene's is a unit sphere's.
inline glm::vec2 directional_planes(const bounds& b) {
  const float r = b.radius > 0.0f ? b.radius : 1.0f;
  return {r, 3.0f * r};
}
inline glm::mat4 directional_view_proj(const bounds& b, const light& l) {
  const float r = directional_planes(b).x;
  const glm::vec3 eye = b.centre - 2.0f * r * glm::normalize(l.direction);
  return glm::orthoRH_ZO(-r, r, -r, r, r, 3.0f * r) * view_along(eye, l.direction);
}

// The shape that bounds a light's reach, whatever the camera.
inline volume shape_of(const light& l) {
  if (l.kind == light_kind::directional) return volume::fullscreen;
  if (l.kind == light_kind::spot && l.outer_angle <= widest_cone) return volume::cone;
  return volume::sphere;
}

}  // namespace frame_detail

inline result<bool> fits_device(const options& o, int largest) {
  const int wanted = std::max({o.width, o.height, o.shadow_size});
  if (wanted > largest)
    return failure{"a " + std::to_string(o.width) + "x" + std::to_string(o.height) + " frame with a " +
                   std::to_string(o.shadow_size) + "^2 shadow map needs images " + std::to_string(wanted) +
                   " texels a side; this device's largest is " + std::to_string(largest)};
  return true;
}

inline result<bool> materials_fit(const scene& s, std::uint64_t most_texels) {
  const std::uint64_t wanted = std::uint64_t(s.materials.size()) * (sizeof(material_block) / sizeof(glm::vec4));
  if (wanted > most_texels)
    return failure{std::to_string(s.materials.size()) + " materials need " + std::to_string(wanted) +
                   " texels of a texel buffer; this device's largest holds " + std::to_string(most_texels)};
  return true;
}

inline volume volume_of(const light& l, const options& o) { return o.fullscreen_lights ? volume::fullscreen : frame_detail::shape_of(l); }

inline volume_model particle_model(const options& o) {
  if (o.particles == options::particle_light::moments) return light_moments();
  if (o.particles == options::particle_light::four_axes) return on_axes(four_axes());
  basis b = six_axes();
  if (o.particles == options::particle_light::fourteen_axes)  // a user-supplied set: the cube's faces and corners
    for (int i = 0; i < 8; ++i) b.axes.push_back(glm::normalize(glm::vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1)));
  return on_axes(b);
}

inline volume_atlas particle_atlas(const scene& s, const options& o) {
  std::vector<volume_grid> grids;
  const int n = std::clamp(o.volume_cells, 1, 256);
  for (const particle_system& ps : s.particles) {
    const auto [lo, hi] = particle_bounds(ps);
    grids.push_back(fit_grid(lo, hi, glm::ivec3(n)));
  }
  return pack_volumes(grids, particle_model(o).texels());
}

inline std::vector<particle_region> particle_regions(const scene& s, const particle_plan& smoke) {
  std::vector<particle_region> out;
  const volume_atlas& a = smoke.atlas;
  for (std::size_t r = 0; r < a.regions.size() && r < s.particles.size(); ++r) {
    const volume_grid& g = a.regions[r];
    out.push_back({glm::vec4(glm::vec3(g.origin), float(s.particles[r].material)), glm::vec4(glm::vec3(g.scale), float(a.slab)),
                   glm::vec4(glm::vec3(a.offsets[r]), smoke.ranges[r]), glm::vec4(glm::vec3(g.dims), 0.0f)});
  }
  return out;
}

inline particle_plan particle_plan_of(const scene& s, const frame_plan& p, const options& o) {
  return particle_plan_of(s, p, o, light_blocks(s));
}

inline particle_plan particle_plan_of(const scene& s, const frame_plan& p, const options& o, const std::vector<light_block>& lights) {
  if (lights.size() != s.lights.size()) return particle_plan_of(s, p, o);
  particle_plan out;
  out.on = p.on.has(effect::light_volumes) && !p.forward;
  out.reference = out.on && (o.particles == options::particle_light::forward || p.exact);
  out.baking = out.on && !out.reference;
  out.atlas = particle_atlas(s, o);
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const light_block& b = lights[i];
    const volume_light v{glm::vec4(glm::vec3(b.position_range), b.direction_kind.w),
                         glm::vec4(glm::vec3(b.direction_kind), b.position_range.w), b.colour_cos_outer,
                         glm::vec4(b.cos_inner.x, float(i), 0.0f, 0.0f)};
    (p.lookups[i] != shadow_mode::off ? out.shadowed_lights : out.unshadowed_lights).push_back(v);
  }
  out.shadows = out.shadowed_lights.empty() ? shadow_mode::off : p.shadows;
  std::vector<volume_light> all = out.unshadowed_lights;
  all.insert(all.end(), out.shadowed_lights.begin(), out.shadowed_lights.end());
  for (const volume_grid& g : out.atlas.regions) out.ranges.push_back(volume_range(g, all));
  return out;
}

inline bool temporal_interlacing(const options& o, effects on) {
  return o.temporal && o.method == technique::interlaced && on.has(effect::transparency);
}

inline bool textured_shadows(const scene& s) {
  for (const object& obj : s.objects) {
    if (obj.material >= s.materials.size()) continue;
    const material& m = s.materials[obj.material];
    if (m.textured() && (m.transparent() || m.alpha_cutoff > 0.0f)) return true;
  }
  return false;
}

inline bool rough_refraction(const options& o, effects on) {
  return o.rough_refraction && !is_forward(o.method) && on.has(effect::refraction);
}

inline frame_plan plan_of(const scene& s, const options& o) {
  frame_plan p{};
  effects e = effects_of(scene_features(s));
  if (o.refraction <= 0.0f || o.method == technique::reference) e = e.without(effect::refraction);
  if (o.shadows != shadow_mode::transparent) e = e.without(effect::transparent_shadows);
  if (o.shadows == shadow_mode::off) e = e.without(effect::shadows);
  e.bits |= o.force.bits;  // forced code runs even where the options leave its effect nothing to do
  p.on = completed(e);
  const std::vector<target_desc> light_descs = o.rgb_specular ? describe<rgb_light_buffer>() : describe<thesis_light_buffer>();
  p.pipeline = o.layout == gbuffer_layout::compact ? plan_pipeline<compact_gbuffer>(p.on, light_descs) : plan_pipeline<thesis_gbuffer>(p.on, light_descs);
  p.shadows = !p.on.has(effect::shadows)                ? shadow_mode::off
              : p.on.has(effect::transparent_shadows) ? shadow_mode::transparent
                                                      : shadow_mode::opaque;
  // A light whose cone reaches no glass looks its map up plainly, unless the transparent lookup is forced.
  const std::vector<detail::placed_sphere> glass =
      p.shadows == shadow_mode::transparent ? detail::transparent_spheres(s) : std::vector<detail::placed_sphere>{};
  for (const light& l : s.lights)
    p.lookups.push_back(!casts_shadows(l) || p.shadows == shadow_mode::off ? shadow_mode::off
                        : p.shadows == shadow_mode::transparent &&
                                (detail::first_reached(l, glass) || o.force.has(effect::transparent_shadows))
                            ? shadow_mode::transparent
                            : shadow_mode::opaque);
  p.depth_only_shadows = p.shadows == shadow_mode::transparent && o.opaque_shadows_depth_only;
  p.forward = is_forward(o.method);
  p.forward_depth = o.method == technique::forward_depth;
  p.peeling = o.method == technique::peeling;
  p.temporal = temporal_interlacing(o, p.on);
  p.exact = o.method == technique::reference;
  p.layers = p.forward ? 0 : p.peeling ? 2 : 1;
  p.around_glass = !p.forward && !p.exact && dstrans::around_glass(p.on);
  const bool transparent = p.on.has(effect::transparency) || p.on.has(effect::many_layers) || p.on.has(effect::light_volumes);
  p.lists = p.exact ? transparent : !p.forward && p.on.has(effect::many_layers);
  const bool particle_reference = !p.forward && p.on.has(effect::light_volumes) && o.particles == options::particle_light::forward;
  const bool shadowed = p.uses(shadow_mode::opaque) || p.uses(shadow_mode::transparent);
  p.shadow_layers = shadowed && ((p.exact && transparent) || particle_reference);
  // The previous frame's G-buffer and light buffer, which the compose pass reads.
  if (p.temporal) {
    std::vector<planned_target> history;
    for (const planned_target& t : p.pipeline.targets)
      if (t.name.rfind("gbuffer.", 0) == 0 || t.name.rfind("light.", 0) == 0) {
        history.push_back(t);
        history.back().name = "previous." + t.name;
        p.pipeline.bytes_per_pixel += t.bytes_per_pixel;
      }
    for (planned_pass& pass : p.pipeline.passes)
      if (pass.name == "compose") {
        for (const planned_target& t : history) pass.reads.push_back(t.name);
        pass.switches.push_back("DST_TEMPORAL");
      }
    p.pipeline.targets.insert(p.pipeline.targets.end(), history.begin(), history.end());
  }
  // Forced, the textures reach the shadow pass too (the full pipeline, for comparisons).
  p.textured_shadows = p.on.has(effect::textures) && (textured_shadows(s) || o.force.has(effect::textures));
  if (!p.textured_shadows)
    for (planned_pass& pass : p.pipeline.passes)
      if (pass.name == "shadow")
        pass.switches.erase(std::remove(pass.switches.begin(), pass.switches.end(), effect_switch(effect::textures)),
                            pass.switches.end());
  if (rough_refraction(o, p.on))
    for (planned_pass& pass : p.pipeline.passes)
      if (pass.name == "compose") pass.switches.push_back("DST_ROUGH_REFRACTION");
  // The scene's post-processing chain, on the deferred techniques (it reads the G-buffer): its passes and
  // targets join the plan, each target the final image's format.
  if (!p.forward) {
    p.post = plan_post(s.post, o.method == technique::interlaced && p.on.has(effect::transparency));
    const target_desc t = final_target_desc(o.float_targets);
    for (const post_pass& pass : p.post.passes) {
      std::vector<std::string> reads;
      for (const std::string& in : pass.inputs)
        if (in == "gbuffer")
          for (int k = 0; k < 4; ++k) reads.push_back("gbuffer.RT" + std::to_string(k));
        else reads.push_back(in == "frame" ? "output" : "post." + in);
      p.pipeline.passes.push_back({"post " + pass.name, reads, {"post." + pass.output}, pass.switches});
    }
    for (const std::string& name : p.post.targets) {
      p.pipeline.targets.push_back({"post." + name, info(t.fmt).name, info(t.fmt).bytes_per_pixel, false});
      p.pipeline.bytes_per_pixel += info(t.fmt).bytes_per_pixel;
    }
  }
  return p;
}

inline std::vector<target_desc> gbuffer_targets(gbuffer_layout l) {
  return l == gbuffer_layout::thesis ? describe<thesis_gbuffer>() : describe<compact_gbuffer>();
}

inline std::vector<glm::vec4> gbuffer_clears(gbuffer_layout l) {
  std::vector<glm::vec4> out;
  for (const target_desc& t : gbuffer_targets(l))
    out.push_back(out.empty() ? glm::vec4(0, 0, 0, 1) : t.channels[0] == "depth" ? glm::vec4(1.0f) : glm::vec4(0.0f));
  return out;
}

namespace frame_detail {
// The k-buffer's and the particles' passes of frame plan `p`: over the composed frame, or around the glass
// into the glass layers, which the first of them clears to nothing drawn (no colour, all of what lies
// behind kept).
inline void add_layered(frame_schedule& out, const frame_plan& p, const particle_plan& smoke) {
  const std::string into = p.around_glass ? "glass layers" : "frame";
  // What the passes read of the frame: the G-buffers (around the glass, peeling's second too, for the
  // opaque surface's depth), and the composed frame they draw over.
  std::vector<std::string> frame_reads{"gbuffer"};
  if (p.around_glass && p.peeling) frame_reads.push_back("gbuffer 2");
  if (!p.around_glass) frame_reads.push_back("frame");
  bool first = true;
  auto add = [&](pass_step step, const std::string& timer, const std::string& label, pass_kind kind, std::vector<std::string> reads,
                 std::vector<std::string> writes) -> scheduled_pass& {
    scheduled_pass pass(timer, label, kind, -1, std::move(reads), std::move(writes));
    pass.step = step;
    out.passes.push_back(std::move(pass));
    return out.passes.back();
  };
  auto layered = [&](pass_step step, const std::string& timer, const std::string& label, pass_kind kind, std::vector<std::string> reads) {
    reads.insert(reads.end(), frame_reads.begin(), frame_reads.end());
    scheduled_pass& pass = add(step, timer, label, kind, std::move(reads), {into});
    pass.state.blend = p.around_glass ? blending::layer : blending::over;
    if (p.around_glass && first) pass.clears = {glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)};
    first = false;
  };
  if (p.on.has(effect::many_layers) && !p.forward) {
    std::vector<std::string> reads{"scene", "gbuffer"};
    if (p.around_glass && p.peeling) reads.push_back("gbuffer 2");
    if (p.shadows != shadow_mode::off && hair_shadow_light(p) >= 0) reads.push_back("shadow map");
    // The capture also empties the lists (heads and node count) before it fills them.
    scheduled_pass& c = add(pass_step::capture, "capture", "capture pass", pass_kind::geometry, reads, {"kbuffer"});
    c.state.blend = blending::add;
    c.draws = geometry_set::hair;
    c.clears = {glm::vec4(0.0f), glm::vec4(0.0f)};
    layered(pass_step::resolve, "resolve", "resolve pass", pass_kind::fullscreen, {"kbuffer"});
  }
  if (smoke.on)
    layered(pass_step::particles, "particles", "particle pass", pass_kind::geometry,
            {smoke.baking ? "volume atlas" : smoke.shadowed_lights.empty() ? "scene" : "shadow layers"});
}

// The exact reference's passes over the composed frame: every transparent fragment of the surfaces and hair
// shaded into the lists (the capture empties them first), then the particles', then the resolve.
inline void add_exact(frame_schedule& out, const frame_plan& p, const particle_plan& smoke) {
  if (!p.lists) return;
  std::vector<std::string> reads{"scene", "gbuffer"};
  if (p.shadow_layers) reads.push_back("shadow layers");
  scheduled_pass c("capture", "capture pass", pass_kind::geometry, -1, reads, {"kbuffer"});
  c.step = pass_step::capture;
  c.state.blend = blending::add;
  c.draws = geometry_set::everything;
  c.clears = {glm::vec4(0.0f), glm::vec4(0.0f)};
  out.passes.push_back(c);
  if (smoke.on) {
    reads.push_back("kbuffer");
    scheduled_pass q("particles", "particle pass", pass_kind::geometry, -1, reads, {"kbuffer"});
    q.step = pass_step::particles;
    q.state.blend = blending::add;
    out.passes.push_back(q);
  }
  scheduled_pass r("resolve", "resolve pass", pass_kind::fullscreen, -1, {"kbuffer", "frame"}, {"frame"});
  r.step = pass_step::resolve;
  r.state.blend = blending::over;
  out.passes.push_back(r);
}
}  // namespace frame_detail

inline frame_schedule schedule_of(const scene& s, const frame_plan& p, const options& o) {
  return schedule_of(s, p, o, light_blocks(s));
}

inline frame_schedule schedule_of(const scene& s, const frame_plan& p, const options& o, const std::vector<light_block>& lights) {
  if (lights.size() != s.lights.size()) return schedule_of(s, p, o);
  frame_schedule out;
  auto add = [&](pass_step step, const std::string& timer, const std::string& label, pass_kind kind, int light,
                 std::vector<std::string> reads, std::vector<std::string> writes) -> scheduled_pass& {
    scheduled_pass pass(timer, label, kind, light, std::move(reads), std::move(writes));
    pass.step = step;
    out.passes.push_back(std::move(pass));
    return out.passes.back();
  };
  pass_state depth_tested;  // the geometry passes that fill targets: the nearest fragment wins
  depth_tested.depth = depth_test::less;
  depth_tested.depth_write = true;
  const glm::vec4 zero(0.0f), far_plane(1.0f), opaque_black(0.0f, 0.0f, 0.0f, 1.0f);
  const std::string gbuffer[2] = {"gbuffer", "gbuffer 2"}, light_buffer[2] = {"light buffer", "light buffer 2"};
  for (int k = 0; k < p.layers; ++k) {
    scheduled_pass& g = add(pass_step::gbuffer, "gbuffer", k ? "gbuffer pass, second layer" : "gbuffer pass", pass_kind::geometry, -1,
                            k ? std::vector<std::string>{"scene", gbuffer[0]} : std::vector<std::string>{"scene"}, {gbuffer[k]});
    g.index = k;
    g.state = depth_tested;
    g.draws = geometry_set::surfaces;
    g.clears = gbuffer_clears(o.layout);
    g.clear_depth = true;
    out.cleared.push_back(light_buffer[k]);
  }
  if (p.forward) {
    scheduled_pass& a = add(pass_step::ambient, "ambient", "forward ambient pass", pass_kind::geometry, -1, {"scene"}, {"lit"});
    a.state = depth_tested;
    a.draws = geometry_set::surfaces;
    a.clears = {opaque_black, zero};
    if (p.forward_depth) a.clears.push_back(far_plane);
    a.clear_depth = true;
  }
  const particle_plan smoke = particle_plan_of(s, p, o, lights);
  if (smoke.baking) out.cleared.push_back("volume atlas");
  if (smoke.baking && !smoke.unshadowed_lights.empty())
    add(pass_step::bake, "bake", "bake pass", pass_kind::dispatch, -1, {"scene"}, {"volume atlas"});
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    const int l = int(i);
    const std::string n = std::to_string(i);
    const bool shadowed = p.lookups[i] != shadow_mode::off;
    std::vector<std::string> reads{"scene"};
    if (shadowed) {
      const int views = shadow_views(lights[i]);
      for (int v = 0; v < views; ++v)
        for (const geometry_set set : p.depth_only_shadows ? std::vector<geometry_set>{geometry_set::opaque, geometry_set::not_opaque}
                                            : std::vector<geometry_set>{geometry_set::everything}) {
          const bool first = set != geometry_set::not_opaque;
          scheduled_pass& sh = add(pass_step::shadow, "shadow",
                                   "shadow pass, light " + n + (views > 1 ? ", face " + std::to_string(v) : "") +
                                       (set == geometry_set::opaque ? ", opaque surfaces" : set == geometry_set::not_opaque ? ", the rest" : ""),
                                   pass_kind::geometry, l, {"scene"}, {"shadow map"});
          sh.index = v;
          sh.view_proj = light_frame(s, lights[i], o, v).view_proj;
          sh.state = depth_tested;
          sh.state.cull_closed = true;
          sh.draws = set;
          if (v == 0 && first)  // a cube's later faces keep what the first one cleared
            sh.clears = p.shadows == shadow_mode::transparent ? std::vector<glm::vec4>{far_plane, far_plane} : std::vector<glm::vec4>{far_plane};
          sh.clear_depth = v == 0 && first;
          if (views > 1) {
            const glm::ivec2 size(o.shadow_size);
            const int tile = shader::dst_cube_tile_size(size);
            sh.area = glm::ivec4(shader::dst_cube_tile_origin(v, size), tile, tile);
          }
        }
      if (smoke.baking)
        add(pass_step::bake_light, "bake", "bake pass, light " + n, pass_kind::dispatch, l, {"shadow map"}, {"volume atlas"});
      if (p.shadow_layers)
        add(pass_step::shadow_layer, p.exact ? "shadow layers" : "particles", "shadow map into its layer, light " + n,
            pass_kind::transfer, l, {"shadow map"}, {"shadow layers"});
      reads.push_back("shadow map");
    }
    if (p.forward) {
      scheduled_pass& f = add(pass_step::forward_light, "light", "forward light pass, light " + n, pass_kind::geometry, l, reads, {"lit"});
      f.state.depth = depth_test::less_equal;
      f.state.blend = blending::add;
      f.draws = geometry_set::surfaces;
      continue;
    }
    const bool mesh = volume_of(s.lights[i], o) != volume::fullscreen;
    for (int k = 0; k < p.layers; ++k) {
      std::vector<std::string> layer_reads = reads;
      layer_reads[0] = gbuffer[k];
      scheduled_pass& lp = add(pass_step::light, "light", "light pass, light " + n + (k ? ", second layer" : ""),
                               mesh ? pass_kind::light_volume : pass_kind::fullscreen, l, layer_reads, {light_buffer[k]});
      lp.index = k;
      lp.state.blend = blending::add;
      if (mesh) {
        lp.state.cull = culling::front;
        lp.state.depth_clamp = true;
      }
    }
  }
  if (p.forward) {
    add(pass_step::blend, "blend", "forward blend pass", pass_kind::fullscreen, -1, {"lit"}, {"frame"});
  } else {
    std::vector<std::string> reads{gbuffer[0]};
    // Light buffers start cleared: a scene without lights composes its ambient term alone.
    if (!s.lights.empty()) reads.push_back(light_buffer[0]);
    if (p.peeling) {
      reads.push_back(gbuffer[1]);
      if (!s.lights.empty()) reads.push_back(light_buffer[1]);
    }
    // Temporal interlacing: what the previous frame left, which no pass of this frame writes.
    if (p.temporal) reads.insert(reads.end(), {"previous gbuffer", "previous light buffer"});
    if (p.around_glass) {
      frame_detail::add_layered(out, p, smoke);
      reads.push_back("glass layers");
    }
    add(pass_step::compose, "compose", "compose pass", pass_kind::fullscreen, -1, reads, {"frame"});
  }
  if (p.exact) frame_detail::add_exact(out, p, smoke);
  else if (!p.around_glass) frame_detail::add_layered(out, p, smoke);
  for (std::size_t k = 0; k < p.post.passes.size(); ++k) {
    const post_pass& pass = p.post.passes[k];
    std::vector<std::string> reads;
    for (const std::string& in : pass.inputs) reads.push_back(in == "gbuffer" ? gbuffer[0] : in);
    add(pass_step::post, "post " + pass.effect, "post " + pass.name, pass_kind::fullscreen, -1, reads, {pass.output}).index = int(k);
  }
  return out;
}

inline int hair_shadow_light(const frame_plan& p) {
  for (std::size_t i = p.lookups.size(); i-- > 0;)
    if (p.lookups[i] != shadow_mode::off) return int(i);
  return -1;
}

inline frame_block camera_frame(const scene& s, const options& o) { return camera_frame(s, s.view, o); }

inline frame_block camera_frame(const scene& s, const camera& c, const options& o) {
  frame_block f{};
  f.view = c.view();
  const glm::mat4 projection = c.projection(float(o.width) / float(o.height));
  f.view_proj = projection * f.view;
  f.inv_view_proj = glm::inverse(f.view_proj);
  f.camera_position = glm::vec4(c.position, 0.5f * float(o.height) * projection[1][1]);
  f.ambient = glm::vec4(s.ambient, 0.0f);
  f.size = {o.width, o.height, o.shadow_size, o.shadow_size};
  f.params = {o.refraction, o.shadow_bias, -1.0f, float(o.kbuffer_k)};
  f.to_previous = f.from_previous = glm::mat4(1.0f);
  f.counts = {int(s.lights.size()), 0, 0, 0};
  return f;
}

inline glm::ivec2 interlace_phase(predicate p, std::uint64_t index) {
  const int odd = int(index % 2u);
  return p == predicate::rows ? glm::ivec2(0, odd) : glm::ivec2(odd, 0);
}

inline frame_block sequence_frame(frame_block f, const frame_block& previous, std::uint64_t index, const frame_plan& p,
                                  const options& o) {
  f.params.z = float(hair_shadow_light(p));
  if (!p.temporal) return f;
  f.interlace = glm::ivec4(interlace_phase(o.interlace, index), index > 0 ? 1 : 0, index > 0 && previous.view_proj == f.view_proj ? 1 : 0);
  if (index > 0) {  // composed in double: a still camera's is the identity within float's rounding
    f.to_previous = glm::mat4(glm::dmat4(previous.view_proj) * glm::inverse(glm::dmat4(f.view_proj)));
    f.from_previous = glm::mat4(glm::dmat4(f.view_proj) * glm::inverse(glm::dmat4(previous.view_proj)));
  }
  return f;
}

inline bool still_camera(const frame_block& f) { return f.interlace.w == 1; }

inline int shadow_views(const light_block& l) { return shader::dst_map_cube(l.cos_inner) ? 6 : 1; }

inline frame_block light_frame(const scene& s, const light_block& l, const options& o, int view) {
  frame_block f = camera_frame(s, o);
  f.view_proj = l.shadow_view_proj;
  if (shadow_views(l) > 1) f.view_proj = l.shadow_view_proj * frame_detail::cube_face_view(glm::vec3(l.position_range), view);
  return f;
}

inline std::vector<material_block> material_blocks(const scene& s) {
  std::vector<material_block> out;
  for (const material& m : s.materials) {
    // A texture index out of range samples nothing; the layer of an invalid texture is white.
    const bool sampled = m.textured() && m.texture >= 0 && std::size_t(m.texture) < s.textures.size();
    const texture* t = sampled ? &s.textures[std::size_t(m.texture)] : nullptr;
    const float cutoff = m.textured() && m.alpha_cutoff > 0.0f ? m.alpha_cutoff : 0.0f;
    out.push_back({glm::vec4(m.diffuse, m.alpha), glm::vec4(m.spec_intensity, m.spec_power, m.refractive ? 1.0f : 0.0f, m.hair ? 1.0f : 0.0f),
                   glm::vec4(t ? float(m.texture) : -1.0f, cutoff, m.transparent() || cutoff > 0.0f ? 1.0f : 0.0f,
                             t ? float(int(t->wrap_s) + 3 * int(t->wrap_t)) : 0.0f)});
  }
  return out;
}

inline std::vector<light_block> light_blocks(const scene& s) {
  std::vector<light_block> out;
  const frame_detail::bounds b = frame_detail::scene_bounds(s);
  for (const light& l : s.lights) {
    const bool directional = l.kind == light_kind::directional;
    const glm::vec2 planes = directional ? frame_detail::directional_planes(b) : frame_detail::shadow_planes(b, l);
    light_block lb{};
    const float kind = l.kind == light_kind::directional ? 0.0f : l.kind == light_kind::point ? 1.0f : 2.0f;
    lb.position_range = glm::vec4(l.position, l.range);
    lb.direction_kind = glm::vec4(l.direction, kind);
    lb.colour_cos_outer = glm::vec4(l.colour * l.intensity, std::cos(glm::radians(l.outer_angle)));
    // y: 1 for a perspective map, 2 for an orthographic one, 3 for a cube (dst_shadow_map).
    const float map = !casts_shadows(l) ? 0.0f : directional ? 2.0f : l.kind == light_kind::point ? 3.0f : 1.0f;
    lb.cos_inner = glm::vec4(std::cos(glm::radians(l.inner_angle)), map, planes.x, planes.y);
    // The shadow map covers the outer cone; a 90-degree spot would need a 180-degree frustum, so
    // shadow maps stop at 85 degrees and what lies outside them is lit unshadowed. A 0-degree spot lights
    // only its axis, which a frustum of 1 degree holds (one of 0 degrees has an infinite projection).
    const float half = std::clamp(l.outer_angle, 0.5f, 85.0f);
    if (l.kind == light_kind::spot)
      lb.shadow_view_proj = glm::perspectiveRH_ZO(glm::radians(2.0f * half), 1.0f, planes.x, planes.y) * frame_detail::spot_view(l);
    if (directional) lb.shadow_view_proj = frame_detail::directional_view_proj(b, l);
    // A cube's faces share this projection; each face's view is the shaders' (dst_cube_face_view).
    if (l.kind == light_kind::point) lb.shadow_view_proj = glm::perspectiveRH_ZO(glm::radians(90.0f), 1.0f, planes.x, planes.y);
    switch (frame_detail::shape_of(l)) {
      case volume::fullscreen: lb.volume = glm::mat4(1.0f); break;
      case volume::sphere: lb.volume = glm::scale(glm::translate(glm::mat4(1.0f), l.position), glm::vec3(l.range)); break;
      case volume::cone: {
        // The unit cone opens along +Z; a half turn about Y points it down the view space -Z, which the
        // inverse view turns to the light's direction (a rotation: the winding stays outward).
        const float r = l.range * std::tan(glm::radians(l.outer_angle));
        const glm::mat4 turn = glm::inverse(frame_detail::spot_view(l)) * glm::scale(glm::mat4(1.0f), glm::vec3(-1, 1, -1));
        lb.volume = turn * glm::scale(glm::mat4(1.0f), glm::vec3(r, r, l.range));
        break;
      }
    }
    out.push_back(lb);
  }
  return out;
}

}  // namespace dstrans::render

// The GLSL of each pass of the thesis's renderer: generated layout code, the interlace predicate, and the
// hand-written pass shaders of shaders/glsl/, which bring the shared formulas they call.
#pragma once

#include <cstdint>
#include <string>

#include <dstrans/gbuffer.hpp>
#include <dstrans/glsl.hpp>
#include <dstrans/result.hpp>

#include "frame_data.hpp"

namespace dstrans::render {

// Table 3.2's fields in RGBA32F, for options::float_targets.
using float_light_buffer = layout<light_sample, target<format::rgba32f, field::light, field::specular>>;
// The light buffer's targets, and its layout's GLSL, for the options' precision.
std::vector<target_desc> light_targets(bool float_targets);
void add_light_layout(glsl::source& src, const std::string& name, bool float_targets, const glsl::layout_options& o);
// The final image's target.
target_desc final_target_desc(bool float_targets);

// Table 3.3 for transparent shadows; a plain depth map for opaque ones.
using opaque_shadow_map = layout<surface, target<format::r32f, field::depth>>;

// Texture bindings: the G-buffer's four targets, the shadow map's two, the light buffer; for depth
// peeling also the second layer's light buffer and G-buffer, and the first layer's depth.
constexpr int gbuffer_binding = 0, shadow_binding = 4, light_binding = 6, light2_binding = 7, gbuffer2_binding = 8,
              peel_depth_binding = 13;
// The blocks of shaders/glsl/frame.glsl; Vulkan puts them in the same set as the textures.
constexpr int frame_binding = 20, materials_binding = 21, lights_binding = 22;

// Which G-buffer a G-buffer pass writes.
enum class layer { interlaced, first, second };

struct pass_sources {
  glsl::source vertex, fragment;
};

// The interlace predicate `p` (dst_interlace_keep, dst_interlace_partner) into `src`.
void add_predicate(glsl::source& src, predicate p);
// The G-buffer layout `l` under `name`: its targets, what it clears them to (empty pixels are opaque black
// at the far plane), and its GLSL; a read side of the compact layout takes depth from the depth
// attachment at the binding Table 3.1's depth target would have (first_binding + 3).
std::vector<target_desc> gbuffer_targets(gbuffer_layout l);
std::vector<glm::vec4> gbuffer_clears(gbuffer_layout l);
void add_gbuffer_layout(glsl::source& src, gbuffer_layout l, const std::string& name, glsl::layout_options o);
constexpr int gbuffer_depth_slot = 3;  // the depth attachment's binding after a compact G-buffer's first

// `dir` is the folder of the pass shaders (shaders/glsl).
result<pass_sources> gbuffer_pass(const std::string& dir, layer which, effects on, const options& o);
result<pass_sources> shadow_pass(const std::string& dir, shadow_mode mode, effects on);
result<pass_sources> light_pass(const std::string& dir, shadow_mode mode, bool volume, const options& o);
result<pass_sources> compose_pass(const std::string& dir, effects on, const options& o);

// The k-buffer (many_layers): hair into per-pixel lists (or the tail targets), then the resolve over the
// frame with the options' k and variant. `shadows` is the shadow map's kind.
result<pass_sources> capture_pass(const std::string& dir, shadow_mode shadows, const options& o);
result<pass_sources> resolve_pass(const std::string& dir, shadow_mode shadows, const options& o);
// Its node pool's size and tail targets.
std::uint32_t kbuffer_capacity(const options& o);
// The bytes of a frame's render targets, shadow maps and k-buffer lists, for the resource budget.
std::size_t frame_bytes(const frame_plan& p, const options& o);
std::vector<target_desc> kbuffer_tail_targets();
// Texture bindings of the tail targets in the resolve pass; image and buffer bindings of the lists.
constexpr int kbuffer_tail_binding = 14, kbuffer_nodes_binding = 23, kbuffer_heads_binding = 24;

// Light volumes (light_volumes, TECHNIQUES.md S2). The bake of options' basis: all unshadowed lights
// (`shadows` off), or one shadowed spot light reading the shadow map of kind `shadows` through the
// bake's shadow hook. The particle pass: lit from the atlas, or (options::particle_light::forward) by
// every light, reading the shadow maps' copies in layers.
result<glsl::source> bake_pass(const std::string& dir, shadow_mode shadows, const options& o);
result<pass_sources> particle_pass(const std::string& dir, shadow_mode shadows, const options& o);
// Bindings: the bake's lights, the atlas's texels and the region block (add_light_volume_bake's three);
// the particle pass's regions, the atlas, and the shadow maps' layers (depth, colour).
constexpr int volume_lights_binding = 25, volume_texels_binding = 26, volume_region_binding = 27,
              particle_regions_binding = 28, volume_atlas_binding = 29, shadow_layers_binding = 30;

// A pass of the post-processing chain (post.hpp): the full-screen triangle and the pass's shader, its
// texture inputs at post_input_binding and the next, its parameters' block at post_params_binding, the
// G-buffer at its bindings if the pass reads "gbuffer".
result<pass_sources> post_pass_sources(const std::string& dir, const post_pass& pass, const options& o);
constexpr int post_input_binding = 32, post_params_binding = 34;

// Every shader variant the deferred pipeline of `plan` compiles for scene `s`, named as its passes and
// programs are labelled ("gbuffer pass", "light pass transparent shadows volume", ...).
struct named_pass {
  std::string name;
  pass_sources sources;
};
result<std::vector<named_pass>> pipeline_passes(const std::string& dir, const scene& s, const frame_plan& plan,
                                                const options& o);

// The forward renderer's passes: ambient (colour, normal, depth), one light, and the blend.
enum class forward_stage { ambient, light, blend };
result<pass_sources> forward_pass(const std::string& dir, forward_stage stage, bool with_depth, shadow_mode mode,
                                  bool physical_transmittance = false);
// Its targets: lit colour and alpha (RGBA32F with float targets), the normal, and with depth the window depth.
std::vector<target_desc> forward_targets(bool with_depth, bool float_targets = false);

}  // namespace dstrans::render

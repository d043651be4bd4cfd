// The GLSL of each pass of the thesis's renderer: generated layout code, the interlace predicate, and the
// hand-written pass shaders of shaders/glsl/, which bring the shared formulas they call.
#pragma once

#include <cstdint>
#include <string>

#include <dstrans/gbuffer.hpp>
#include <dstrans/frame/slots.hpp>
#include <dstrans/glsl.hpp>
#include <dstrans/pass_shaders.hpp>
#include <dstrans/result.hpp>

#include <dstrans/frame/plan.hpp>

namespace dstrans::render {

// Table 3.2's fields in RGBA32F, for options::float_targets.
using float_light_buffer = layout<light_sample, target<format::rgba32f, field::light, field::specular>>;
// The light buffer's targets, and its layout's GLSL, for the options' precision.
std::vector<target_desc> light_targets(bool float_targets);
void add_light_layout(glsl::source& src, const std::string& name, bool float_targets, const glsl::layout_options& o);

// Table 3.3 for transparent shadows; a plain depth map for opaque ones.
using opaque_shadow_map = layout<surface, target<format::r32f, field::depth>>;


// Which G-buffer a G-buffer pass writes.
enum class layer { interlaced, first, second };

// A pass's GLSL so far: the slot table (dstrans/frame/slots.hpp), which the pass shaders' bindings name.
glsl::source pass_source();
struct pass_sources {
  glsl::source vertex = pass_source(), fragment = pass_source();
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

// `shaders` are the pass shaders: the embedded ones, or a folder's.
result<pass_sources> gbuffer_pass(const pass_shaders& shaders, layer which, effects on, const options& o);
result<pass_sources> shadow_pass(const pass_shaders& shaders, shadow_mode mode, effects on);
result<pass_sources> light_pass(const pass_shaders& shaders, shadow_mode mode, bool volume, const options& o);
result<pass_sources> compose_pass(const pass_shaders& shaders, effects on, const options& o);

// The k-buffer (many_layers): hair into per-pixel lists (or the tail targets), then the resolve over the
// frame with the options' k and variant. `shadows` is the shadow map's kind.
result<pass_sources> capture_pass(const pass_shaders& shaders, shadow_mode shadows, const options& o);
result<pass_sources> resolve_pass(const pass_shaders& shaders, shadow_mode shadows, const options& o);
// Its node pool's size and tail targets.
std::uint32_t kbuffer_capacity(const options& o);
// The bytes of a frame's render targets, shadow maps and k-buffer lists, for the resource budget.
std::size_t frame_bytes(const frame_plan& p, const options& o);
std::vector<target_desc> kbuffer_tail_targets();

// Light volumes (light_volumes, TECHNIQUES.md S2). The bake of options' basis: all unshadowed lights
// (`shadows` off), or one shadowed spot light reading the shadow map of kind `shadows` through the
// bake's shadow hook. The particle pass: lit from the atlas, or (options::particle_light::forward) by
// every light, reading the shadow maps' copies in layers.
result<glsl::source> bake_pass(const pass_shaders& shaders, shadow_mode shadows, const options& o);
result<pass_sources> particle_pass(const pass_shaders& shaders, shadow_mode shadows, const options& o);

// A pass of the post-processing chain (post.hpp): the full-screen triangle and the pass's shader, its
// texture inputs at slot::post_input and the next, its parameters' block at slot::post_params, the
// G-buffer at its slot if the pass reads "gbuffer".
result<pass_sources> post_pass_sources(const pass_shaders& shaders, const post_pass& pass, const options& o);

// Every shader variant the deferred pipeline of `plan` compiles for scene `s`, named as its passes and
// programs are labelled ("gbuffer pass", "light pass transparent shadows volume", ...).
struct named_pass {
  std::string name;
  pass_sources sources;
};
result<std::vector<named_pass>> pipeline_passes(const pass_shaders& shaders, const scene& s, const frame_plan& plan,
                                                const options& o);

// The forward renderer's passes: ambient (colour, normal, depth), one light, and the blend.
enum class forward_stage { ambient, light, blend };
result<pass_sources> forward_pass(const pass_shaders& shaders, forward_stage stage, bool with_depth, shadow_mode mode,
                                  bool physical_transmittance = false);
// Its targets: lit colour and alpha (RGBA32F with float targets), the normal, and with depth the window depth.
std::vector<target_desc> forward_targets(bool with_depth, bool float_targets = false);

}  // namespace dstrans::render

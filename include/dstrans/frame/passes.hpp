// The GLSL of each pass of the frame: generated layout code, the interlace predicate, and the pass shaders
// (dstrans/pass_shaders.hpp), which bring the shared formulas they call. The backends compile these; an
// engine that runs its own passes may take any one of them.
//
//   const dstrans::pass_shaders shaders;                 // embedded
//   auto gbuffer = dstrans::render::gbuffer_pass(shaders, dstrans::render::layer::interlaced, plan.on, options);
//   if (gbuffer) compile(gbuffer->vertex.text(), gbuffer->fragment.text());
#pragma once

#include <cstdint>
#include <string>

#include "../fullscreen.hpp"
#include "../gbuffer.hpp"
#include "../glsl.hpp"
#include "../pass_shaders.hpp"
#include "../result.hpp"
#include "plan.hpp"
#include "slots.hpp"

namespace dstrans::render {

// Table 3.2's and rgb_light_buffer's fields in RGBA32F, for options::float_targets.
using float_light_buffer = layout<light_sample, target<format::rgba32f, field::light, field::specular>>;
using float_rgb_light_buffer = layout<light_sample, target<format::rgba32f, field::light, unused<1>>,
                                      target<format::rgba32f, field::specular_rgb, unused<1>>>;
// The light buffer's targets, and its layout's GLSL, for the options' precision and specular.
std::vector<target_desc> light_targets(const options& o);
void add_light_layout(glsl::source& src, const std::string& name, const options& o, const glsl::layout_options& lo);

// Table 3.3 for transparent shadows; a plain depth map for opaque ones.
using opaque_shadow_map = layout<surface, target<format::r32f, field::depth>>;


// Which G-buffer a G-buffer pass writes.
enum class layer { interlaced, first, second };

// A pass's GLSL so far: the slot table (dstrans/frame/slots.hpp), which the pass shaders' bindings name.
glsl::source pass_source();
struct pass_sources {
  glsl::source vertex = pass_source(), fragment = pass_source();
};

// The interlace predicate `p` (dst_interlace_keep, dst_interlace_partner, or named `as`: glsl::add_interlace)
// into `src`.
void add_predicate(glsl::source& src, predicate p, const std::string& as = "dst_interlace");
// The G-buffer layout `l`'s GLSL under `name` (its targets: render::gbuffer_targets); a read side of the
// compact layout takes depth from the depth attachment at the binding Table 3.1's depth target would have
// (first_binding + 3).
void add_gbuffer_layout(glsl::source& src, gbuffer_layout l, const std::string& name, glsl::layout_options o);
constexpr int gbuffer_depth_slot = 3;  // the depth attachment's binding after a compact G-buffer's first

// `shaders` are the pass shaders: the embedded ones, or a folder's.
result<pass_sources> gbuffer_pass(const pass_shaders& shaders, layer which, effects on, const options& o);
// `opaque_surfaces`: the pass of a transparent map's opaque surfaces (frame_plan::depth_only_shadows), which
// writes their depth and the clear colour without reading their material (DST_DEPTH_ONLY).
result<pass_sources> shadow_pass(const pass_shaders& shaders, shadow_mode mode, effects on, bool opaque_surfaces = false);
result<pass_sources> light_pass(const pass_shaders& shaders, shadow_mode mode, bool volume, const options& o);
// With temporal interlacing, the compose pass has a variant for frames whose camera stood still since the
// previous one (frame_block::interlace.w): `still_camera` (DST_STILL_CAMERA).
result<pass_sources> compose_pass(const pass_shaders& shaders, effects on, const options& o, bool still_camera = false);

// The k-buffer (many_layers): hair into per-pixel lists (or the tail targets), then the resolve over the
// frame with the options' k and variant, or with `around` (frame_plan::around_glass) into the glass layers.
// `shadows` is the shadow map's kind. In the exact reference (technique::reference) the capture takes every
// transparent fragment of the surfaces and hair, shaded fully, reading the shadow maps' layers and, where
// the effects `on` have textures, the materials' textures; its resolve blends every fragment in order.
result<pass_sources> capture_pass(const pass_shaders& shaders, shadow_mode shadows, const options& o, bool around, effects on);
result<pass_sources> resolve_pass(const pass_shaders& shaders, shadow_mode shadows, const options& o, bool around);
// Its node pool's size (its tail targets: dstrans::kbuffer_tail_targets).
std::uint32_t kbuffer_capacity(const options& o);
// The bytes of a frame's render targets, shadow maps (and their layers) and k-buffer lists, for the resource
// budget (the light volumes' atlas is not among them).
std::size_t frame_bytes(const frame_plan& p, const options& o);

// Light volumes (light_volumes: baked lighting for particles, light_volume.hpp). The bake of options' model: all unshadowed lights
// (`shadows` off), or one shadowed spot light reading the shadow map of kind `shadows` through the
// bake's shadow hook. The particle pass: lit from the atlas, or (options::particle_light::forward) by
// every light, reading the shadow maps' copies in layers; over the frame, or with `around` into the glass
// layers; in the exact reference, by every light into the per-pixel lists.
result<glsl::source> bake_pass(const pass_shaders& shaders, shadow_mode shadows, const options& o);
result<pass_sources> particle_pass(const pass_shaders& shaders, shadow_mode shadows, const options& o, bool around);

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
// The options' transmittance and specular apply to the light stage; of the effects `on`, textures apply to
// the ambient and light stages.
result<pass_sources> forward_pass(const pass_shaders& shaders, forward_stage stage, bool with_depth, shadow_mode mode, effects on,
                                  const options& o = {});
// Its targets: lit colour and alpha (RGBA32F with float targets), the normal, and with depth the window depth.
std::vector<target_desc> forward_targets(bool with_depth, bool float_targets = false);

// Definitions.
namespace pass_detail {


using I = interlace::rows;  // the shadow maps' predicate

// `src` with the frame interface (and the fragment helpers, for a fragment shader) and then `files`
// appended, the pass shader last, their #ifdef DST_ sections resolved on `switches`; a failure if a
// file is missing.
inline result<bool> finish(glsl::source& src, const pass_shaders& shaders, std::vector<std::string> files,
                    const std::vector<std::string>& switches = {}) {
  if (files.back().find(".frag.") != std::string::npos) files.insert(files.begin(), "fragment.glsl");
  files.insert(files.begin(), "frame.glsl");
  for (const std::string& f : files)
    if (auto ok = shaders.add_to(src, f, switches); !ok) return ok;
  return true;
}

inline void add_shadow_layout(glsl::source& src, shadow_mode mode, glsl::side side) {
  glsl::layout_options o;
  o.sides = side;
  o.first_binding = binding(slot::shadow_map);
  if (mode == shadow_mode::transparent) glsl::add_layout<thesis_shadow_map>(src, "shadow", o);
  else glsl::add_layout<opaque_shadow_map>(src, "shadow", o);
}

// A lookup's shadow map (its read side) and the radius of its filter in texels (options::shadow_filter),
// a constant the lookup's loops unroll on.
inline void add_shadow_lookup(glsl::source& src, shadow_mode mode, const options& o) {
  add_shadow_layout(src, mode, glsl::side::read);
  src.add("const int dst_shadow_filter_radius = " + std::to_string(std::max(o.shadow_filter, 1) / 2) + ";\n", __FILE__, __LINE__);
}

// The switches of a shadow lookup (or of a shadow map's pass).
inline std::vector<std::string> shadow_switches(shadow_mode mode) {
  if (mode == shadow_mode::off) return {};
  if (mode == shadow_mode::opaque) return {effect_switch(effect::shadows)};
  return {effect_switch(effect::shadows), effect_switch(effect::transparent_shadows)};
}

// The textures switch, where `on` has the effect (the geometry passes sample the materials' textures).
inline std::vector<std::string> texture_switches(effects on) {
  if (!on.has(effect::textures)) return {};
  return {effect_switch(effect::textures)};
}

inline result<pass_sources> scene_vertex(const pass_shaders& shaders, pass_sources p, const std::vector<std::string>& switches = {}) {
  if (auto ok = pass_detail::finish(p.vertex, shaders, {"gbuffer.vert.glsl"}, switches); !ok) return failure{ok.error()};
  return p;
}


// What the k-buffer passes share: the G-buffer's and shadow map's read side, the hair lighting switches.
inline void add_layers_inputs(glsl::source& src, shadow_mode shadows, const options& o, std::vector<std::string>& switches) {
  glsl::layout_options read;
  read.sides = glsl::side::read;
  read.first_binding = binding(slot::gbuffer);
  add_gbuffer_layout(src, o.layout, "gbuffer", read);
  if (shadows != shadow_mode::off) {
    pass_detail::add_shadow_layout(src, shadows, glsl::side::read);
    switches.push_back(effect_switch(effect::shadows));
  }
  switches.push_back(effect_switch(effect::many_layers));
}

// What the passes that draw around the glass read besides the G-buffer (around_glass.glsl): the G-buffer's
// interlace predicate, as dst_gbuffer_interlace_partner (the particles' reference may look shadow maps up
// under the generic names), or peeling's second layer.
inline void add_around_glass(glsl::source& src, const options& o, std::vector<std::string>& switches) {
  switches.push_back(around_glass_switch);
  if (o.method == technique::interlaced) {
    add_predicate(src, o.interlace, "dst_gbuffer_interlace");
    return;
  }
  glsl::layout_options read;
  read.sides = glsl::side::read;
  read.first_binding = binding(slot::gbuffer2);
  add_gbuffer_layout(src, o.layout, "gbuffer2", read);
  switches.push_back("DST_PEELED");
}
}  // namespace pass_detail

inline glsl::source pass_source() {
  glsl::source src;
  add_slots(src);
  return src;
}

inline void add_predicate(glsl::source& src, predicate p, const std::string& as) {
  switch (p) {
    case predicate::rows: glsl::add_interlace<interlace::rows>(src, as); break;
    case predicate::columns: glsl::add_interlace<interlace::columns>(src, as); break;
    case predicate::checker: glsl::add_interlace<interlace::checker>(src, as); break;
  }
}

inline void add_gbuffer_layout(glsl::source& src, gbuffer_layout l, const std::string& name, glsl::layout_options o) {
  if (l == gbuffer_layout::thesis) {
    glsl::add_layout<thesis_gbuffer>(src, name, o);
  } else {
    if (o.sides == glsl::side::read) o.depth_attachment_binding = o.first_binding + gbuffer_depth_slot;
    glsl::add_layout<compact_gbuffer>(src, name, o);
  }
}

inline result<pass_sources> gbuffer_pass(const pass_shaders& shaders, layer which, effects on, const options& opt) {
  pass_sources p;
  std::vector<std::string> switches = pass_detail::texture_switches(on);
  if (which == layer::second) switches.push_back("DST_PEEL");
  if (opt.method == technique::reference) switches.push_back("DST_OPAQUE_ONLY");
  glsl::layout_options o;
  o.sides = glsl::side::write;
  add_gbuffer_layout(p.fragment, opt.layout, "gbuffer", o);
  // The first peeled layer keeps every nearest fragment, transparent or not.
  if (which == layer::interlaced && on.has(effect::transparency) && opt.method == technique::interlaced) {
    switches.push_back(effect_switch(effect::transparency));
    add_predicate(p.fragment, opt.interlace);
  }
  if (auto ok = pass_detail::finish(p.fragment, shaders, {"gbuffer.frag.glsl"}, switches); !ok) return failure{ok.error()};
  return pass_detail::scene_vertex(shaders, std::move(p), pass_detail::texture_switches(on));
}

inline result<pass_sources> shadow_pass(const pass_shaders& shaders, shadow_mode mode, effects on, bool opaque_surfaces) {
  pass_sources p;
  pass_detail::add_shadow_layout(p.fragment, mode, glsl::side::write);
  if (mode == shadow_mode::transparent) glsl::add_interlace<pass_detail::I>(p.fragment);
  std::vector<std::string> switches = pass_detail::shadow_switches(mode);
  if (opaque_surfaces) switches.push_back("DST_DEPTH_ONLY");
  if (on.has(effect::many_layers)) switches.push_back(effect_switch(effect::many_layers));
  for (const std::string& s : pass_detail::texture_switches(on)) switches.push_back(s);
  if (auto ok = pass_detail::finish(p.fragment, shaders, {"shadow.frag.glsl"}, switches); !ok) return failure{ok.error()};
  return pass_detail::scene_vertex(shaders, std::move(p), pass_detail::texture_switches(on));
}

namespace pass_detail {
// The switches of lighting.glsl's dst_light_at_point that the options turn on.
inline std::vector<std::string> light_switches(const options& o) {
  std::vector<std::string> out;
  if (o.physical_transmittance) out.push_back("DST_TRANSMITTANCE");
  if (o.rgb_specular) out.push_back("DST_RGB_SPECULAR");
  return out;
}
// Calls visit(L{}) with the light buffer layout L of the options.
template <class Visit>
void with_light_layout(const options& o, Visit&& visit) {
  if (o.rgb_specular) {
    if (o.float_targets) visit(float_rgb_light_buffer{});
    else visit(rgb_light_buffer{});
  } else if (o.float_targets) {
    visit(float_light_buffer{});
  } else {
    visit(thesis_light_buffer{});
  }
}
}  // namespace pass_detail

inline std::vector<target_desc> light_targets(const options& o) {
  std::vector<target_desc> out;
  pass_detail::with_light_layout(o, [&](auto l) { out = describe<decltype(l)>(); });
  return out;
}

inline void add_light_layout(glsl::source& src, const std::string& name, const options& o, const glsl::layout_options& lo) {
  pass_detail::with_light_layout(o, [&](auto l) { glsl::add_layout<decltype(l)>(src, name, lo); });
}

inline result<pass_sources> light_pass(const pass_shaders& shaders, shadow_mode mode, bool volume, const options& o) {
  pass_sources p;
  p.vertex.add_shared(text::dst_fullscreen);
  if (auto ok = pass_detail::finish(p.vertex, shaders, {"light.vert.glsl"}, volume ? std::vector<std::string>{"DST_LIGHT_VOLUME"} : std::vector<std::string>{}); !ok)
    return failure{ok.error()};
  std::vector<std::string> switches = pass_detail::shadow_switches(mode);
  for (const std::string& s : pass_detail::light_switches(o)) switches.push_back(s);
  glsl::layout_options read;
  read.sides = glsl::side::read;
  read.first_binding = binding(slot::gbuffer);
  add_gbuffer_layout(p.fragment, o.layout, "gbuffer", read);
  glsl::layout_options write;
  write.sides = glsl::side::write;
  add_light_layout(p.fragment, "light", o, write);
  if (mode != shadow_mode::off) pass_detail::add_shadow_lookup(p.fragment, mode, o);
  if (mode == shadow_mode::transparent) glsl::add_interlace<pass_detail::I>(p.fragment);
  if (auto ok = pass_detail::finish(p.fragment, shaders, {"lighting.glsl", "light.frag.glsl"}, switches); !ok) return failure{ok.error()};
  return p;
}

inline result<pass_sources> compose_pass(const pass_shaders& shaders, effects on, const options& o, bool still_camera) {
  // The exact reference's G-buffer holds only opaque surfaces: it composes them alone.
  if (o.method == technique::reference) on = on.without(effect::transparency).without(effect::refraction);
  pass_sources p;
  p.vertex = glsl::fullscreen_vertex_shader();
  glsl::layout_options read;
  read.sides = glsl::side::read;
  read.first_binding = binding(slot::gbuffer);
  add_gbuffer_layout(p.fragment, o.layout, "gbuffer", read);
  read.first_binding = binding(slot::light);
  add_light_layout(p.fragment, "light", o, read);
  std::vector<std::string> switches;
  for (effect e : {effect::transparency, effect::refraction})
    if (on.has(e)) switches.push_back(effect_switch(e));
  if (rough_refraction(o, on)) switches.push_back("DST_ROUGH_REFRACTION");
  if (!is_forward(o.method) && around_glass(on)) switches.push_back(around_glass_switch);
  std::string other = "interlaced.glsl";
  const bool temporal = temporal_interlacing(o, on);
  if (o.method == technique::interlaced) {
    if (on.has(effect::transparency)) add_predicate(p.fragment, o.interlace);
    if (on.has(effect::transparency) && o.reconstruct) switches.push_back("DST_RECONSTRUCT");
    if (temporal) switches.push_back("DST_TEMPORAL");
    if (temporal && still_camera) switches.push_back("DST_STILL_CAMERA");
  } else {
    other = "peeled.glsl";
  }
  // Peeling's second layer, or the previous frame's.
  if (o.method == technique::peeling || temporal) {
    read.first_binding = binding(slot::gbuffer2);
    add_gbuffer_layout(p.fragment, o.layout, "gbuffer2", read);
    read.first_binding = binding(slot::light2);
    add_light_layout(p.fragment, "light2", o, read);
  }
  // Without transparency the compose pass never asks for the other layer.
  std::vector<std::string> files{"compose.frag.glsl"};
  if (on.has(effect::transparency)) files.insert(files.begin(), other);
  if (auto ok = pass_detail::finish(p.fragment, shaders, files, switches); !ok) return failure{ok.error()};
  return p;
}

inline result<std::vector<named_pass>> pipeline_passes(const pass_shaders& shaders, const scene& s, const frame_plan& plan,
                                                const options& o) {
  std::vector<named_pass> out;
  auto add = [&](const std::string& name, result<pass_sources> p) -> result<bool> {
    if (!p) return failure{p.error()};
    out.push_back({name, std::move(*p)});
    return true;
  };
  if (auto ok = add("gbuffer pass", gbuffer_pass(shaders, layer::interlaced, plan.on, o)); !ok) return failure{ok.error()};
  if (plan.shadows != shadow_mode::off)
    if (auto ok = add("shadow pass", shadow_pass(shaders, plan.shadows, plan.shadow_effects())); !ok) return failure{ok.error()};
  if (plan.depth_only_shadows)
    if (auto ok = add("shadow pass, opaque surfaces", shadow_pass(shaders, plan.shadows, effects{}, true)); !ok) return failure{ok.error()};
  for (shadow_mode k : all_lookups)
    for (int vol = 0; vol < 2; ++vol) {
      bool used = false;
      for (std::size_t i = 0; i < s.lights.size(); ++i)
        used = used || (plan.lookups[i] == k && (volume_of(s.lights[i], o) != volume::fullscreen) == (vol == 1));
      if (!used) continue;
      const std::string name = std::string("light pass") + lookup_label(k) + (vol ? " volume" : " fullscreen");
      if (auto ok = add(name, light_pass(shaders, k, vol == 1, o)); !ok) return failure{ok.error()};
    }
  if (auto ok = add("compose pass", compose_pass(shaders, plan.on, o)); !ok) return failure{ok.error()};
  if (plan.temporal)
    if (auto ok = add("compose pass still camera", compose_pass(shaders, plan.on, o, true)); !ok) return failure{ok.error()};
  if (plan.lists) {
    if (auto ok = add("capture pass", capture_pass(shaders, plan.shadows, o, plan.around_glass, plan.on)); !ok) return failure{ok.error()};
    if (auto ok = add("resolve pass", resolve_pass(shaders, plan.shadows, o, plan.around_glass)); !ok) return failure{ok.error()};
  }
  if (plan.on.has(effect::light_volumes))
    if (auto ok = add("particle pass", particle_pass(shaders, plan.shadows, o, plan.around_glass)); !ok) return failure{ok.error()};
  for (const post_pass& pass : plan.post.passes)
    if (auto ok = add("post " + pass.name, post_pass_sources(shaders, pass, o)); !ok) return failure{ok.error()};
  return out;
}


inline std::uint32_t kbuffer_capacity(const options& o) {
  if (o.kbuffer_nodes) return o.kbuffer_nodes;
  return std::uint32_t(kbuffer_nodes_per_pixel) * std::uint32_t(o.width) * std::uint32_t(o.height);
}

inline std::size_t frame_bytes(const frame_plan& p, const options& o) {
  const std::size_t pixels = std::size_t(o.width) * std::size_t(o.height), texels = std::size_t(o.shadow_size) * std::size_t(o.shadow_size);
  std::size_t bytes = 0, shadow_texel = 0;
  for (const planned_target& t : p.pipeline.targets) {
    // The lists are counted below at the pool's size, which the options set; the glass layers only where
    // they are drawn (not in the exact reference).
    if (t.volume || t.name.rfind("kbuffer.", 0) == 0 || (!p.around_glass && t.name.rfind("glass.", 0) == 0)) continue;
    if (t.shadow_map) {
      shadow_texel += std::size_t(t.bytes_per_pixel);
      continue;
    }
    // The plan counts the previous frame's G-buffer of temporal interlacing, not peeling's second.
    const bool layer = t.name.rfind("gbuffer.", 0) == 0 || t.name.rfind("light.", 0) == 0;
    bytes += std::size_t(t.bytes_per_pixel) * pixels * (p.peeling && layer ? 2u : 1u);
  }
  std::size_t maps = 1;
  if (p.shadow_layers)
    for (shadow_mode m : p.lookups) maps += m != shadow_mode::off ? 1u : 0u;
  bytes += shadow_texel * texels * maps;
  if (p.lists) {
    bytes += std::size_t(kbuffer_capacity(o)) * std::size_t(kbuffer_node_bytes) + pixels * 4u;
    for (const target_desc& t : kbuffer_tail_targets()) bytes += std::size_t(info(t.fmt).bytes_per_pixel) * pixels;
  }
  return bytes;
}

inline result<pass_sources> capture_pass(const pass_shaders& shaders, shadow_mode shadows, const options& o, bool around, effects on) {
  pass_sources p;
  std::vector<std::string> switches;
  if (o.method == technique::reference) {
    if (shadows != shadow_mode::off) {
      for (const std::string& s : pass_detail::shadow_switches(shadows)) switches.push_back(s);
      if (auto ok = shaders.add_to(p.fragment, "shadow_layers.glsl", switches); !ok) return failure{ok.error()};
      pass_detail::add_shadow_lookup(p.fragment, shadows, o);
      if (shadows == shadow_mode::transparent) glsl::add_interlace<pass_detail::I>(p.fragment);
    }
    glsl::layout_options read;
    read.sides = glsl::side::read;
    read.first_binding = binding(slot::gbuffer);
    add_gbuffer_layout(p.fragment, o.layout, "gbuffer", read);
    switches.push_back(effect_switch(effect::many_layers));
    for (const std::string& s : pass_detail::light_switches(o)) switches.push_back(s);
    for (const std::string& s : pass_detail::texture_switches(on)) switches.push_back(s);
    const std::vector<std::string> files{"lighting.glsl", "lists.glsl", "kbuffer.glsl", "exact_capture.frag.glsl"};
    if (auto ok = pass_detail::finish(p.fragment, shaders, files, switches); !ok) return failure{ok.error()};
    return pass_detail::scene_vertex(shaders, std::move(p), pass_detail::texture_switches(on));
  }
  pass_detail::add_layers_inputs(p.fragment, shadows, o, switches);
  if (around) pass_detail::add_around_glass(p.fragment, o, switches);
  if (o.kbuffer_variant == options::layers::wboit) switches.push_back("DST_LAYERS_WBOIT");
  if (auto ok = pass_detail::finish(p.fragment, shaders, {"around_glass.glsl", "lists.glsl", "kbuffer.glsl", "capture.frag.glsl"}, switches); !ok)
    return failure{ok.error()};
  return pass_detail::scene_vertex(shaders, std::move(p));
}

inline result<pass_sources> resolve_pass(const pass_shaders& shaders, shadow_mode shadows, const options& o, bool around) {
  pass_sources p;
  p.vertex = glsl::fullscreen_vertex_shader();
  if (o.method == technique::reference) {
    if (auto ok = pass_detail::finish(p.fragment, shaders, {"lists.glsl", "exact_resolve.frag.glsl"}); !ok) return failure{ok.error()};
    return p;
  }
  std::vector<std::string> switches;
  pass_detail::add_layers_inputs(p.fragment, shadows, o, switches);
  if (around) pass_detail::add_around_glass(p.fragment, o, switches);
  // The forward reference keeps up to 64 fragments in order and shades its tail fully too.
  const int k = o.kbuffer_variant == options::layers::forward ? 64 : std::clamp(o.kbuffer_k, 1, 32);
  p.fragment.add("#define DST_K " + std::to_string(k) + "\n", "dstrans/frame/passes.hpp", 1);
  if (o.kbuffer_variant == options::layers::tailless) switches.push_back("DST_LAYERS_TAILLESS");
  if (o.kbuffer_variant == options::layers::cheap) switches.push_back("DST_LAYERS_CHEAP");
  if (o.kbuffer_variant == options::layers::forward) switches.push_back("DST_LAYERS_FORWARD");
  if (o.kbuffer_variant == options::layers::deferred || o.kbuffer_variant == options::layers::cheap)
    switches.push_back("DST_LAYERS_GATHERED");
  if (auto ok = pass_detail::finish(p.fragment, shaders, {"around_glass.glsl", "lists.glsl", "kbuffer.glsl", "resolve.frag.glsl"}, switches); !ok)
    return failure{ok.error()};
  return p;
}

inline result<glsl::source> bake_pass(const pass_shaders& shaders, shadow_mode shadows, const options& o) {
  glsl::source src = pass_source();
  std::string hook;
  if (shadows != shadow_mode::off) {
    pass_detail::add_shadow_lookup(src, shadows, o);
    if (shadows == shadow_mode::transparent) glsl::add_interlace<pass_detail::I>(src);
    if (auto ok = pass_detail::finish(src, shaders, {"lighting.glsl"}, pass_detail::shadow_switches(shadows)); !ok) return failure{ok.error()};
    // The light's own entry in the frame's lights holds its shadow map's matrix (particle_plan's lights).
    hook = "vec3 dst_volume_shadow(dst_volume_light l, vec3 p, vec3 light) {\n"
           "  return dst_shadowed(light, p, lights[int(l.cos_inner.y + 0.5f)]);\n"
           "}\n";
  }
  static_assert(binding(slot::volume_image) == binding(slot::volume_lights) + 1 &&
                    binding(slot::volume_regions) == binding(slot::volume_lights) + 2,
                "the bake takes its lights, atlas and regions at three consecutive bindings");
  glsl::add_light_volume_bake(src, particle_model(o), binding(slot::volume_lights), hook);
  return src;
}

inline result<pass_sources> particle_pass(const pass_shaders& shaders, shadow_mode shadows, const options& o, bool around) {
  pass_sources p;
  std::vector<std::string> switches;
  const bool exact = o.method == technique::reference;  // lit by the forward reference, into the lists
  if (o.particles == options::particle_light::forward || exact) {
    switches.push_back("DST_PARTICLES_FORWARD");
    if (shadows != shadow_mode::off) {
      for (const std::string& s : pass_detail::shadow_switches(shadows)) switches.push_back(s);
      if (auto ok = shaders.add_to(p.fragment, "shadow_layers.glsl", switches); !ok) return failure{ok.error()};
      pass_detail::add_shadow_lookup(p.fragment, shadows, o);
      if (shadows == shadow_mode::transparent) glsl::add_interlace<pass_detail::I>(p.fragment);
    }
  } else {
    glsl::add_light_volume_fetch(p.vertex, particle_model(o));
    glsl::add_light_volume_read(p.fragment, particle_model(o));
  }
  if (auto ok = pass_detail::finish(p.vertex, shaders, {"particle.vert.glsl"}, switches); !ok) return failure{ok.error()};
  glsl::layout_options read;
  read.sides = glsl::side::read;
  read.first_binding = binding(slot::gbuffer);
  add_gbuffer_layout(p.fragment, o.layout, "gbuffer", read);
  std::vector<std::string> fragment_switches = switches;
  if (around) pass_detail::add_around_glass(p.fragment, o, fragment_switches);
  std::vector<std::string> files{"around_glass.glsl", "particle.frag.glsl"};
  if (exact) {
    fragment_switches.push_back("DST_EXACT");
    files.insert(files.begin() + 1, "lists.glsl");
  }
  if ((o.particles == options::particle_light::forward || exact) && shadows != shadow_mode::off) files.insert(files.begin(), "lighting.glsl");
  if (auto ok = pass_detail::finish(p.fragment, shaders, files, fragment_switches); !ok) return failure{ok.error()};
  return p;
}

inline result<pass_sources> post_pass_sources(const pass_shaders& shaders, const post_pass& pass, const options& o) {
  pass_sources p;
  p.vertex = glsl::fullscreen_vertex_shader();
  for (const std::string& in : pass.inputs)
    if (in == "gbuffer") {
      glsl::layout_options read;
      read.sides = glsl::side::read;
      read.first_binding = binding(slot::gbuffer);
      add_gbuffer_layout(p.fragment, o.layout, "gbuffer", read);
    }
  for (const std::string& sw : pass.switches)
    if (sw == "DST_AA_INTERLACE") add_predicate(p.fragment, o.interlace);
  if (auto ok = pass_detail::finish(p.fragment, shaders, {"post.glsl", pass.shader}, pass.switches); !ok) return failure{ok.error()};
  return p;
}

inline std::vector<target_desc> forward_targets(bool with_depth, bool float_targets) {
  std::vector<target_desc> t{{float_targets ? format::rgba32f : format::rgba8, {"colour.r", "colour.g", "colour.b", "alpha"}},
                             {format::rgb10a2, {"normal.x", "normal.y", "normal.z", "unused"}}};
  if (with_depth) t.push_back({format::r32f, {"depth"}});
  return t;
}

inline result<pass_sources> forward_pass(const pass_shaders& shaders, forward_stage stage, bool with_depth, shadow_mode mode, effects on,
                                         const options& o) {
  pass_sources p;
  std::vector<std::string> switches;
  if (stage != forward_stage::blend) switches = pass_detail::texture_switches(on);
  if (with_depth) switches.push_back("DST_FORWARD_DEPTH");
  if (stage == forward_stage::light) {
    for (const std::string& s : pass_detail::shadow_switches(mode)) switches.push_back(s);
    for (const std::string& s : pass_detail::light_switches(o)) switches.push_back(s);
    if (mode != shadow_mode::off) pass_detail::add_shadow_lookup(p.fragment, mode, o);
  }
  glsl::add_interlace<pass_detail::I>(p.fragment);
  std::vector<std::string> files;
  switch (stage) {
    case forward_stage::ambient: files = {"forward.glsl", "forward_ambient.frag.glsl"}; break;
    case forward_stage::light: files = {"lighting.glsl", "forward.glsl", "forward_light.frag.glsl"}; break;
    case forward_stage::blend: files = {"forward_blend.frag.glsl"}; break;
  }
  if (auto ok = pass_detail::finish(p.fragment, shaders, files, switches); !ok) return failure{ok.error()};
  if (stage == forward_stage::blend) {
    p.vertex = glsl::fullscreen_vertex_shader();
    return p;
  }
  if (auto ok = pass_detail::finish(p.vertex, shaders, {"forward.vert.glsl"}, switches); !ok) return failure{ok.error()};
  return p;
}

}  // namespace dstrans::render

// The deferred pipeline a set of effects needs: its passes, what each reads and
// writes, the shader switches each compiles with, and its render targets. Only the effects in the set
// get a pass, a target or a switch.
//
//   // at run time, from a scene
//   dstrans::pipeline_plan p = dstrans::plan_pipeline(dstrans::effects_of(dstrans::scene_features(s)));
//   // at compile time: the set is a template argument, and the plan's figures are constants
//   using glass = dstrans::pipeline<dstrans::effect_set<dstrans::effect::transparency>>;
//   static_assert(glass::screen_bytes_per_pixel == 20 && !glass::has_shadow_colour);
//   dstrans::pipeline_plan same = glass::plan();
//
// Both go through pipeline<E>::plan(): plan_pipeline picks the instantiation for its set. Pass shaders
// test the switches with #ifdef; glsl::source::add_file resolves them, so a shader's text holds no code
// for an effect that is off.
#pragma once

#include <string>
#include <vector>

#include "gbuffer.hpp"
#include "scene_features.hpp"

namespace dstrans {

// A render target (or buffer) of the plan: a Table's target, the shadow map's (one set, reused by every
// light), the k-buffer's, or the light volumes'.
struct planned_target {
  std::string name;    // "gbuffer.RT0", ..., "light.RT0", "shadow.depth", "shadow.colour", "kbuffer.heads", ...
  std::string format;  // as the thesis's tables name formats ("RGBA8"), or "R32UI", or "buffer"
  int bytes_per_pixel;  // a pixel, or a texel of the shadow map or the volume atlas
  bool shadow_map;     // sized as the shadow map, not the screen
  bool volume = false;  // sized as the light volumes' atlas (its model's texels a cell), not the screen
};

// The k-buffer's node pool, in nodes per screen pixel: fragments that find the pool used up go to the
// tail (S1 keeps every fragment). 16 a pixel holds hair over 40% of the screen at 21 layers (hair.json).
constexpr int kbuffer_nodes_per_pixel = 16, kbuffer_node_bytes = 16;

struct planned_pass {
  std::string name;                   // gbuffer, shadow (once per shadow-casting light), light, compose
  std::vector<std::string> reads;     // targets sampled
  std::vector<std::string> writes;    // targets drawn into
  std::vector<std::string> switches;  // the pass shader's #ifdef switches that are on
};

struct pipeline_plan {
  effects on;
  std::vector<planned_pass> passes;
  std::vector<planned_target> targets;
  // Screen-sized targets, in bytes a pixel (the thesis's 20: Table 3.1's G-buffer and the light buffer).
  int bytes_per_pixel = 0;

  const planned_target* target(const std::string& name) const {
    for (const planned_target& t : targets)
      if (t.name == name) return &t;
    return nullptr;
  }
  const planned_pass* pass(const std::string& name) const {
    for (const planned_pass& p : passes)
      if (p.name == name) return &p;
    return nullptr;
  }
};

// Whether a deferred frame with effects `e` draws hair and particles around its glass layer: into two
// premultiplied targets, one with what lies between the glass and the opaque surface behind it and one with
// what lies in front of the glass, which the compose pass puts in depth order around the glass.
constexpr bool around_glass(effects e) {
  return e.has(effect::transparency) && (e.has(effect::many_layers) || e.has(effect::light_volumes));
}

// The switch of the passes that draw around the glass (around_glass).
inline constexpr const char* around_glass_switch = "DST_AROUND_GLASS";

// The glass layers (around_glass): what lies behind a pixel's glass and what lies in front of it, each
// premultiplied, with in alpha what it keeps of what lies behind it.
inline std::vector<target_desc> glass_layer_targets() {
  return {{format::rgba16f, {"behind.r", "behind.g", "behind.b", "behind.kept"}},
          {format::rgba16f, {"front.r", "front.g", "front.b", "front.kept"}}};
}
// The k-buffer's tail targets: premultiplied colour and alpha, and optical depth, added out of order.
inline std::vector<target_desc> kbuffer_tail_targets() {
  return {{format::rgba16f, {"tail.r", "tail.g", "tail.b", "tail.alpha"}}, {format::r16f, {"optical_depth"}}};
}

// E: the effect set; G: the G-buffer's layout (Table 3.1's, or compact_gbuffer with depth from the depth
// attachment, which the plan does not count, as every renderer has one).
template <class E, class G = thesis_gbuffer>
struct pipeline {
  static constexpr effects set = E::value;
  static constexpr bool interlaced = set.has(effect::transparency);
  static constexpr bool refracts = set.has(effect::refraction);
  static constexpr bool has_shadows = set.has(effect::shadows);
  static constexpr bool has_shadow_colour = set.has(effect::transparent_shadows);
  static constexpr bool many_layers = set.has(effect::many_layers);
  static constexpr bool light_volumes = set.has(effect::light_volumes);
  static constexpr bool textured = set.has(effect::textures);
  static constexpr int screen_bytes_per_pixel = G::bytes_per_pixel + thesis_light_buffer::bytes_per_pixel;
  static constexpr int shadow_bytes_per_texel = !has_shadows         ? 0
                                                : has_shadow_colour ? thesis_shadow_map::bytes_per_pixel
                                                                    : info(format::r32f).bytes_per_pixel;
  static_assert(!refracts || interlaced, "refraction bends the light through transparent surfaces: it needs transparency");
  static_assert(!has_shadow_colour || has_shadows, "transparent shadows are shadows: they need the shadows effect");

  // `light`: the light buffer's targets (the thesis's by default; render::light_targets gives the others).
  static pipeline_plan plan(const std::vector<target_desc>& light_descs = describe<thesis_light_buffer>()) {
    pipeline_plan p;
    p.on = set;
    auto add_targets = [&](const std::vector<target_desc>& descs, const std::string& name, bool shadow_map) {
      std::vector<std::string> names;
      for (std::size_t i = 0; i < descs.size(); ++i) {
        names.push_back(name + ".RT" + std::to_string(i));
        p.targets.push_back({names.back(), info(descs[i].fmt).name, info(descs[i].fmt).bytes_per_pixel, shadow_map});
      }
      return names;
    };
    const std::vector<std::string> gbuffer = add_targets(describe<G>(), "gbuffer", false);
    // Where depth is read: the G-buffer's depth target, or the depth attachment.
    std::string depth = "gbuffer.depth";
    const std::vector<target_desc> described = describe<G>();
    for (std::size_t i = 0; i < described.size(); ++i)
      for (const std::string& c : described[i].channels)
        if (c == "depth") depth = gbuffer[i];
    const std::vector<std::string> light = add_targets(light_descs, "light", false);
    std::vector<std::string> shadow;
    if constexpr (has_shadows) {
      p.targets.push_back({"shadow.depth", info(format::r32f).name, info(format::r32f).bytes_per_pixel, true});
      shadow.push_back("shadow.depth");
      if constexpr (has_shadow_colour) {
        p.targets.push_back({"shadow.colour", info(format::rgba8).name, info(format::rgba8).bytes_per_pixel, true});
        shadow.push_back("shadow.colour");
      }
    }
    std::vector<std::string> geometry;  // the G-buffer pass's switches
    if constexpr (interlaced) geometry.push_back(effect_switch(effect::transparency));
    if constexpr (textured) geometry.push_back(effect_switch(effect::textures));
    p.passes.push_back({"gbuffer", {}, gbuffer, geometry});
    std::vector<std::string> lookup;
    if constexpr (has_shadows) {
      lookup.push_back(effect_switch(effect::shadows));
      if constexpr (has_shadow_colour) lookup.push_back(effect_switch(effect::transparent_shadows));
      std::vector<std::string> occluders = lookup;
      if constexpr (textured) occluders.push_back(effect_switch(effect::textures));
      p.passes.push_back({"shadow", {}, shadow, occluders});
    }
    std::vector<std::string> light_reads = gbuffer;
    light_reads.insert(light_reads.end(), shadow.begin(), shadow.end());
    p.passes.push_back({"light", light_reads, light, lookup});
    std::vector<std::string> compose_reads = gbuffer, compose;
    compose_reads.insert(compose_reads.end(), light.begin(), light.end());
    if constexpr (interlaced) compose.push_back(effect_switch(effect::transparency));
    if constexpr (refracts) compose.push_back(effect_switch(effect::refraction));
    // Hair and particles over the composed image, or around the glass into their own targets before it.
    std::vector<std::string> layered{"output"};
    if constexpr (around_glass(set)) {
      layered = {"glass.behind", "glass.front"};
      const std::vector<target_desc> made = glass_layer_targets();
      for (std::size_t i = 0; i < made.size(); ++i)
        p.targets.push_back({layered[i], info(made[i].fmt).name, info(made[i].fmt).bytes_per_pixel, false});
      compose_reads.insert(compose_reads.end(), layered.begin(), layered.end());
      compose.push_back(around_glass_switch);
    } else {
      p.passes.push_back({"compose", compose_reads, {"output"}, compose});
    }
    if constexpr (many_layers) {
      // S1: hair fragments in front of the opaque surfaces into per-pixel lists (their overflow into the
      // tail targets), then the resolve over the composed image or around the glass.
      const std::vector<std::string> lists{"kbuffer.heads", "kbuffer.nodes"}, tail{"kbuffer.tail", "kbuffer.transmittance"};
      p.targets.push_back({"kbuffer.heads", "R32UI", 4, false});
      p.targets.push_back({"kbuffer.nodes", "buffer", kbuffer_nodes_per_pixel * kbuffer_node_bytes, false});
      const std::vector<target_desc> made = kbuffer_tail_targets();
      for (std::size_t i = 0; i < made.size(); ++i)
        p.targets.push_back({tail[i], info(made[i].fmt).name, info(made[i].fmt).bytes_per_pixel, false});
      std::vector<std::string> capture_writes = lists, resolve_reads = lists;
      capture_writes.insert(capture_writes.end(), tail.begin(), tail.end());
      resolve_reads.insert(resolve_reads.end(), tail.begin(), tail.end());
      resolve_reads.push_back(depth);
      if (has_shadows) resolve_reads.push_back("shadow.depth");
      std::vector<std::string> on{effect_switch(effect::many_layers)};
      if constexpr (around_glass(set)) on.push_back(around_glass_switch);
      p.passes.push_back({"capture", {depth}, capture_writes, on});
      p.passes.push_back({"resolve", resolve_reads, layered, on});
    }
    if constexpr (light_volumes) {
      // S2: the light of each system's bounds baked into its region of the atlas (added to in place,
      // RGBA8 as S2 stored it), each shadowed spot light's dispatch right after its shadow pass; the
      // particles, sorted, over the frame or around the glass.
      p.targets.push_back({"volume.atlas", info(format::rgba8).name, info(format::rgba8).bytes_per_pixel, false, true});
      std::vector<std::string> on{effect_switch(effect::light_volumes)};
      p.passes.push_back({"bake", shadow, {"volume.atlas"}, on});
      if constexpr (around_glass(set)) on.push_back(around_glass_switch);
      p.passes.push_back({"particles", {"volume.atlas", depth}, layered, on});
    }
    if constexpr (around_glass(set)) p.passes.push_back({"compose", compose_reads, {"output"}, compose});
    for (const planned_target& t : p.targets)
      if (!t.shadow_map && !t.volume) p.bytes_per_pixel += t.bytes_per_pixel;
    return p;
  }
};

namespace detail {
template <unsigned Bits>
struct bits_set {
  static constexpr effects value{Bits};
};
template <unsigned Bits, class G>
pipeline_plan plan_bits(unsigned bits, const std::vector<target_desc>& light) {
  if constexpr (Bits == effects::all().bits + 1u) {
    return {};
  } else {
    // Sets that pipeline<> rejects (refraction without transparency, transparent shadows without shadows)
    // are completed first by plan_pipeline, so they never reach here.
    constexpr effects e{Bits};
    if constexpr ((!e.has(effect::refraction) || e.has(effect::transparency)) &&
                  (!e.has(effect::transparent_shadows) || e.has(effect::shadows)))
      if (bits == Bits) return pipeline<bits_set<Bits>, G>::plan(light);
    return plan_bits<Bits + 1u, G>(bits, light);
  }
}
}  // namespace detail

// The effects `e` needs with the ones they depend on: refraction brings transparency, transparent
// shadows bring shadows.
constexpr effects completed(effects e) {
  if (e.has(effect::refraction)) e = e.with(effect::transparency);
  if (e.has(effect::transparent_shadows)) e = e.with(effect::shadows);
  return e;
}

// The plan for set `e` (completed) with G-buffer layout G and light-buffer targets `light`, through the
// same pipeline<E, G>::plan() a compile-time caller uses.
template <class G = thesis_gbuffer>
pipeline_plan plan_pipeline(effects e, const std::vector<target_desc>& light = describe<thesis_light_buffer>()) {
  return detail::plan_bits<0u, G>(completed(e).bits, light);
}

}  // namespace dstrans

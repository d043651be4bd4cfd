// Every binding slot the reference pipeline's passes use, declared once: C++ binds by slot (binding()),
// the GLSL of every pass gets the table as #defines (add_slots: DST_SLOT_FRAME, ...), which the pass
// shaders' layout qualifiers name, and a GL backend saves and restores exactly these bindings.
//
//   glBindBufferBase(GL_UNIFORM_BUFFER, dstrans::binding(dstrans::slot::frame), frame_ubo);
//   dstrans::glsl::source src;
//   dstrans::add_slots(src);   // "#define DST_SLOT_FRAME 20" ...: layout(std140, binding = DST_SLOT_FRAME)
//
// Vulkan puts every slot in descriptor set 0, so no two slots share a binding number, whatever their kind.
#pragma once

#include <string>

#include "../glsl.hpp"

namespace dstrans {

// The names of the slots, in table order.
enum class slot {
  gbuffer,           // the G-buffer's targets (a compact layout's depth attachment at its fourth)
  shadow_map,        // the shadow map's depth and colour
  light,             // the light buffer's targets (two with RGB specular)
  light2,            // depth peeling: the second layer's light buffer
  gbuffer2,          // depth peeling: the second layer's G-buffer
  peel_depth,        // depth peeling: the first layer's depth, which the second peels behind
  kbuffer_tail,      // the k-buffer's tail: its colour and optical depth
  forward_lit,       // forward rendering: the lit colour, the normal and (with depth) the depth
  frame,             // the frame block (frame/blocks.hpp)
  materials,         // the materials, three RGBA32F texels each (frame.glsl's dst_material)
  lights,            // the lights
  kbuffer_nodes,     // the k-buffer's node pool
  kbuffer_heads,     // the k-buffer's list heads
  volume_lights,     // the light-volume bake: its lights, the atlas as a storage image, the regions it bakes
  volume_image,
  volume_regions,
  particle_regions,  // the particle pass: each system's atlas region, the atlas, the shadow maps' layers
  volume_atlas,
  shadow_layers,
  post_input,        // a post-processing pass: its input images and its parameters
  post_params,
  material_textures, // the scene's textures as one array (material_textures.hpp), for the geometry passes
  glass_layers,      // the compose pass: what hair and particles lay behind and in front of the glass
};

// What a slot binds: sampled textures (a texture unit each on GL), a storage image, a uniform block, a
// storage block, a buffer read as texels (GL: a buffer texture on a texture unit; Vulkan: a uniform texel
// buffer).
enum class slot_kind { texture, image, uniform_block, storage_block, texel_buffer };

struct slot_desc {
  slot id;
  const char* name;  // the GLSL define's suffix: DST_SLOT_<name>
  int binding;       // the first binding
  int count;         // consecutive bindings from the first
  slot_kind kind;
};

inline constexpr slot_desc slot_table[] = {
    {slot::gbuffer, "GBUFFER", 0, 4, slot_kind::texture},
    {slot::shadow_map, "SHADOW_MAP", 4, 2, slot_kind::texture},
    {slot::light, "LIGHT", 6, 2, slot_kind::texture},
    {slot::light2, "LIGHT2", 8, 2, slot_kind::texture},
    {slot::gbuffer2, "GBUFFER2", 10, 4, slot_kind::texture},
    {slot::peel_depth, "PEEL_DEPTH", 14, 1, slot_kind::texture},
    {slot::kbuffer_tail, "KBUFFER_TAIL", 15, 2, slot_kind::texture},
    {slot::forward_lit, "FORWARD_LIT", 17, 3, slot_kind::texture},
    {slot::frame, "FRAME", 20, 1, slot_kind::uniform_block},
    {slot::materials, "MATERIALS", 21, 1, slot_kind::texel_buffer},
    {slot::lights, "LIGHTS", 22, 1, slot_kind::storage_block},
    {slot::kbuffer_nodes, "KBUFFER_NODES", 23, 1, slot_kind::storage_block},
    {slot::kbuffer_heads, "KBUFFER_HEADS", 24, 1, slot_kind::image},
    {slot::volume_lights, "VOLUME_LIGHTS", 25, 1, slot_kind::storage_block},
    {slot::volume_image, "VOLUME_IMAGE", 26, 1, slot_kind::image},
    {slot::volume_regions, "VOLUME_REGIONS", 27, 1, slot_kind::storage_block},
    {slot::particle_regions, "PARTICLE_REGIONS", 28, 1, slot_kind::storage_block},
    {slot::volume_atlas, "VOLUME_ATLAS", 29, 1, slot_kind::texture},
    {slot::shadow_layers, "SHADOW_LAYERS", 30, 2, slot_kind::texture},
    {slot::post_input, "POST_INPUT", 32, 2, slot_kind::texture},
    {slot::post_params, "POST_PARAMS", 34, 1, slot_kind::uniform_block},
    {slot::material_textures, "MATERIAL_TEXTURES", 35, 1, slot_kind::texture},
    {slot::glass_layers, "GLASS_LAYERS", 36, 2, slot_kind::texture},
};

// The first binding of slot `s`.
constexpr int binding(slot s) { return slot_table[int(s)].binding; }

namespace detail {
constexpr bool slots_in_order() {
  for (int i = 0; i < int(sizeof slot_table / sizeof slot_table[0]); ++i)
    if (int(slot_table[i].id) != i) return false;
  return true;
}
constexpr bool slots_disjoint() {
  for (const slot_desc& a : slot_table)
    for (const slot_desc& b : slot_table)
      if (a.id != b.id && a.binding < b.binding + b.count && b.binding < a.binding + a.count) return false;
  return true;
}
}  // namespace detail
static_assert(detail::slots_in_order(), "dstrans slots: slot_table lists the slots in the order enum slot names them");
static_assert(detail::slots_disjoint(), "dstrans slots: two slots share a binding, which Vulkan's one descriptor set cannot hold");

// The largest binding any slot uses, plus one.
constexpr int slot_bindings() {
  int end = 0;
  for (const slot_desc& d : slot_table) end = d.binding + d.count > end ? d.binding + d.count : end;
  return end;
}

// The table as GLSL: "#define DST_SLOT_<NAME> <binding>" for each slot.
inline void add_slots(glsl::source& src) {
  std::string text;
  for (const slot_desc& d : slot_table) text += "#define DST_SLOT_" + std::string(d.name) + " " + std::to_string(d.binding) + "\n";
  src.add(text, __FILE__, __LINE__);
}

}  // namespace dstrans

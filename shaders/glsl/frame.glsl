// What every dstrans pass knows about the frame, the materials and the lights (std140/std430, set 0): the
// blocks of include/dstrans/frame/blocks.hpp, which come with the names, at the slots of
// include/dstrans/frame/slots.hpp, which every pass gets as DST_SLOT_ defines.
#ifdef VULKAN
#define DST_VERTEX_ID gl_VertexIndex
#else
#define DST_VERTEX_ID gl_VertexID
#endif

layout(std140, binding = DST_SLOT_FRAME) uniform dst_frame { dst_frame_data frame; };
// The materials as a texel buffer, three RGBA32F texels each (dst_material_data's vec4s in order): llvmpipe
// and lavapipe gather a texel fetch across the lanes, where they load a storage block lane by lane, and the
// geometry passes read a material per fragment.
layout(binding = DST_SLOT_MATERIALS) uniform samplerBuffer dst_materials;
layout(std430, binding = DST_SLOT_LIGHTS) readonly buffer dst_lights { dst_light_data lights[]; };

// Material `i`.
dst_material_data dst_material(uint i) {
  int t = 3 * int(i);
  return dst_material_data(texelFetch(dst_materials, t), texelFetch(dst_materials, t + 1),
                           texelFetch(dst_materials, t + 2));
}

// One light as flat varyings: what shading reads of it, all but its volume (8 locations). The deferred
// light pass loads its light in the vertex shader, a few vertices a light, and hands it on: llvmpipe and
// lavapipe load a storage block lane by lane, which per fragment cost more than the lighting itself. The
// forward light passes keep the per-fragment load: they draw the whole scene a light, whose vertices
// outnumber its fragments at the sizes measured.
struct dst_light_varying {
  vec4 position_range, direction_kind, colour_cos_outer, cos_inner;
  mat4 shadow_view_proj;
};
dst_light_varying dst_light_varying_of(dst_light_data l) {
  return dst_light_varying(l.position_range, l.direction_kind, l.colour_cos_outer, l.cos_inner, l.shadow_view_proj);
}
dst_light_data dst_light_of(dst_light_varying v) {
  return dst_light_data(v.position_range, v.direction_kind, v.colour_cos_outer, v.cos_inner, v.shadow_view_proj, mat4(0.0f));
}

// The shadow maps of all shadowed lights at once, for the particles' forward reference, which lights a
// fragment by every light in one pass: each map is copied into a layer of these arrays right after it is
// drawn (the light pass reuses one map). dst_shadowed (lighting.glsl) reads layer dst_shadow_layer.
#define DSTRANS_SHADOW_FETCH
int dst_shadow_layer = 0;
layout(binding = DST_SLOT_SHADOW_LAYERS) uniform sampler2DArray dst_shadow_layers_depth;
#ifdef DST_TRANSPARENT_SHADOWS
layout(binding = DST_SLOT_SHADOW_LAYERS + 1) uniform sampler2DArray dst_shadow_layers_colour;
#endif
vec4 dst_shadow_fetch(int target, ivec2 pixel) {
#ifdef DST_TRANSPARENT_SHADOWS
  if (target == 1) return texelFetch(dst_shadow_layers_colour, ivec3(pixel, dst_shadow_layer), 0);
#endif
  return texelFetch(dst_shadow_layers_depth, ivec3(pixel, dst_shadow_layer), 0);
}

// The capture pass (S1): every hair fragment in front of the opaque surfaces goes into its pixel's list; when
// the pool is full it is shaded cheaply and added to the tail targets instead (never dropped). Fragments
// with alpha below 1/255 are dropped. With DST_LAYERS_WBOIT (weighted blended OIT, McGuire and Bavoil
// 2013, the peer) there are no lists: every fragment is shaded fully and added to the tail with its weight.
layout(location = 0) in vec3 world_normal;  // the strand's tangent, for hair
layout(location = 1) flat in uint surface_material;
layout(location = 0) out vec4 tail;           // premultiplied colour and alpha, added
layout(location = 1) out float optical_depth;  // -ln(1 - alpha), added: the tail's transmittance is exp(-x)

void main() {
  dst_material_data m = dst_material(surface_material);
  float alpha = m.diffuse_alpha.w;
  ivec2 p = dst_pixel();
  if (alpha < 1.0f / 255.0f || gl_FragCoord.z >= dst_glass_and_opaque(p).y) discard;
  vec3 tangent = normalize(world_normal);
  vec4 colour_alpha = vec4(m.diffuse_alpha.xyz, alpha);
  optical_depth = -log(max(1.0f - alpha, 1.0f / 1024.0f));
#ifdef DST_LAYERS_WBOIT
  vec3 lit = dst_hair_lit(dst_world_position(p, gl_FragCoord.z), tangent, colour_alpha, true);
  tail = dst_tail_add(vec4(0.0f), vec4(lit, alpha)) * dst_wboit_weight(alpha, gl_FragCoord.z);
  return;
#endif
  if (dst_list_push(p, uvec3(floatBitsToUint(gl_FragCoord.z), dst_pack_tangent(tangent), dst_pack_colour(colour_alpha)))) {
    tail = vec4(0.0f);
    optical_depth = 0.0f;
    return;
  }
  vec3 shaded = dst_hair_lit(dst_world_position(p, gl_FragCoord.z), tangent, colour_alpha, false);
  tail = dst_tail_add(vec4(0.0f), vec4(shaded, alpha));
}

// The hair's lighting (TECHNIQUES.md S1), full (Eq. 2 with Eq. 1's 25 Gaussian shadow taps) or cheap
// (diffuse, one tap), for the k-buffer's passes, whose nodes (lists.glsl) hold its inputs: depth bits,
// tangent, colour and alpha.

#ifdef DST_SHADOWS
// Eq. 1: the share of light that reaches `world` through the hair in front of it, from Gaussian taps of
// the shadow map (radius 2: 25 taps; radius 0: the centre), 50 strands a unit of distance behind the
// first occluder.
float dst_hair_visibility(vec3 world, dst_light_data l, float alpha, int radius) {
  vec4 h = l.shadow_view_proj * vec4(dst_map_view_point(world, l.position_range.xyz, l.cos_inner), 1.0f);
  if (!(h.w > 0.0f)) return 1.0f;
  ivec2 size = frame.size.zw;
  ivec2 origin = dst_map_tile_origin(world, l.position_range.xyz, l.cos_inner, size);
  ivec2 extent = dst_map_tile_extent(l.cos_inner, size);
  ivec2 texel = dst_map_texel(h.xy / h.w, origin, extent, l.cos_inner);
  if (!dst_tile_holds(texel, origin, extent)) return 1.0f;  // where the map does not reach, as dst_shadowed
  float far_plane = l.cos_inner.w;
  float along = far_plane * dst_map_point_depth(h, l.cos_inner);
  float sum = 0.0f, weights = 0.0f;
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      ivec2 t = clamp(texel + ivec2(dx, dy), origin, origin + extent - 1);  // taps stay on the point's tile
      float d = dst_shadow_read(t).depth;
      float occluder = far_plane * dst_map_depth(d, l.cos_inner);  // distance along the light's axis
      float w = dst_shadow_tap_weight(float(dx), float(dy));
      sum += w * dst_hair_transmittance(alpha, 50.0f, along - occluder - 0.01f);
      weights += w;
    }
  return sum / weights;
}
#endif

// The light every lamp of the scene gives a hair fragment, plus the ambient term.
vec3 dst_hair_lit(vec3 world, vec3 tangent, vec4 colour_alpha, bool full) {
  vec3 v = normalize(frame.camera_position.xyz - world);
  vec3 sum = frame.ambient.xyz * colour_alpha.xyz;
  for (int i = 0; i < frame.counts.x; ++i) {
    dst_light_data l = lights[i];
    vec4 reach = dst_light_reach(int(l.direction_kind.w + 0.5f), l.position_range.xyz, l.direction_kind.xyz,
                                 l.position_range.w, l.colour_cos_outer.w, l.cos_inner.x, world);
    vec3 light = l.colour_cos_outer.xyz * reach.w;
    float visibility = 1.0f;
#ifdef DST_SHADOWS
    if (float(i) == frame.params.z) visibility = dst_hair_visibility(world, l, colour_alpha.w, full ? 2 : 0);
#endif
    if (full) sum += dst_hair_full(tangent, vec3(reach), v, colour_alpha.xyz, light, visibility);
    else sum += dst_hair_cheap(tangent, vec3(reach), colour_alpha.xyz, light, visibility);
  }
  return sum;
}

// The light a tail gives its fragments at once (dst_hair_cheap_mean): `colour` is their sum of colour
// times alpha, `world` where they lie on average, `diag` and `off` their mean T T^T, `alpha` their mean
// alpha (for Eq. 1's one tap).
vec3 dst_hair_lit_mean(vec3 world, vec3 diag, vec3 off, vec3 colour, float alpha) {
  vec3 sum = frame.ambient.xyz * colour;
  for (int i = 0; i < frame.counts.x; ++i) {
    dst_light_data l = lights[i];
    vec4 reach = dst_light_reach(int(l.direction_kind.w + 0.5f), l.position_range.xyz, l.direction_kind.xyz,
                                 l.position_range.w, l.colour_cos_outer.w, l.cos_inner.x, world);
    float visibility = 1.0f;
#ifdef DST_SHADOWS
    if (float(i) == frame.params.z) visibility = dst_hair_visibility(world, l, alpha, 0);
#endif
    sum += dst_hair_cheap_mean(diag, off, vec3(reach), colour, l.colour_cos_outer.xyz * reach.w, visibility);
  }
  return sum;
}

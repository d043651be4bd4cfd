// The light one light gives a point: attenuation, spot falloff, the shadow map (DST_SHADOWS: plain, or with
// DST_TRANSPARENT_SHADOWS transparent by Eq. 3.1-3.2; with DST_TRANSMITTANCE by I_L C instead of
// min(I_L, C)) and Phong (Eq. 2.1). Shared by the deferred light pass and the forward light passes.

#ifdef DST_SHADOWS
// Eq. 3.1 at one texel of the map (its interlace partner kept within the tile) for a point at depth d_p.
vec3 dst_shadow_texel(vec3 light, ivec2 texel, ivec2 origin, ivec2 extent, float d_p, float bias, dst_light_data l) {
#ifdef DST_TRANSPARENT_SHADOWS
  ivec2 other = dst_tile_partner(texel, dst_interlace_partner(texel, frame.size.zw), origin, extent);
  dst_surface a = dst_shadow_read(texel), b = dst_shadow_read(other);
  float depth_a = dst_map_depth(a.depth, l.cos_inner), depth_b = dst_map_depth(b.depth, l.cos_inner);
#ifdef DST_TRANSMITTANCE
  return dst_transmitted_shadow(light, d_p, bias, depth_a, vec4(a.diffuse, a.alpha), depth_b, vec4(b.diffuse, b.alpha));
#else
  return dst_transparent_shadow(light, d_p, bias, depth_a, vec4(a.diffuse, a.alpha), depth_b, vec4(b.diffuse, b.alpha));
#endif
#else
  return dst_opaque_shadow(light, d_p, bias, dst_map_depth(dst_shadow_read(texel).depth, l.cos_inner));
#endif
}

// The light that reaches `world` past the shadow map: Eq. 3.1 at its texel, or (soft shadows) its mean
// over the texels within dst_shadow_filter_radius of it, on the point's tile. Depths are compared
// linearly, as fractions of the map's far plane (dst_shadow_map), and the bias (frame.params.y) is a
// fraction of the receiver's distance.
vec3 dst_shadowed(vec3 light, vec3 world, dst_light_data l) {
  vec4 h = l.shadow_view_proj * vec4(dst_map_view_point(world, l.position_range.xyz, l.cos_inner), 1.0f);
  if (!(h.w > 0.0f)) return light;
  ivec2 origin = dst_map_tile_origin(world, l.position_range.xyz, l.cos_inner, frame.size.zw);
  ivec2 extent = dst_map_tile_extent(l.cos_inner, frame.size.zw);
  ivec2 texel = dst_map_texel(h.xy / h.w, origin, extent, l.cos_inner);
  if (!dst_tile_holds(texel, origin, extent)) return light;
  float d_p = dst_map_point_depth(h, l.cos_inner);
  float bias = frame.params.y * d_p;
  vec3 sum = vec3(0.0f);
  for (int dy = -dst_shadow_filter_radius; dy <= dst_shadow_filter_radius; ++dy)
    for (int dx = -dst_shadow_filter_radius; dx <= dst_shadow_filter_radius; ++dx)
      sum += dst_shadow_texel(light, clamp(texel + ivec2(dx, dy), origin, origin + extent - 1), origin, extent, d_p, bias, l);
  int taps = 2 * dst_shadow_filter_radius + 1;
  return sum / float(taps * taps);
}

// A surface's point (unit normal n) is looked up (1 + the filter's radius) texels of the map away along
// its normal (a normal offset): seen at a grazing angle from the light, a surface spans more depth within
// one texel than the bias covers, and would shadow itself in stripes; a filter's outer texels lie farther
// along it. A texel spans 2 w / (s extent) of the map's view plane at depth w (1 for an orthographic
// map), s being its projection's x scale: the length of the first row of shadow_view_proj's rotation part.
vec3 dst_shadowed_surface(vec3 light, vec3 world, vec3 n, dst_light_data l) {
  vec4 h = l.shadow_view_proj * vec4(dst_map_view_point(world, l.position_range.xyz, l.cos_inner), 1.0f);
  float s = length(vec3(l.shadow_view_proj[0][0], l.shadow_view_proj[1][0], l.shadow_view_proj[2][0]));
  float texel = 2.0f * h.w / (s * float(dst_map_tile_extent(l.cos_inner, frame.size.zw).x));
  float offset = texel * float(1 + dst_shadow_filter_radius);
  return dst_shadowed(light, h.w > 0.0f && offset > 0.0f ? world + n * offset : world, l);
}
#endif

// Light `l` at world point `p` with unit normal `n` and Phong exponent `spec_power`, seen from the camera.
// Its specular is the thesis's white one unless DST_RGB_SPECULAR, as the light buffer keeps it, so that
// forward rendering shades as the deferred light buffer does.
dst_light_sample dst_light_at_point(dst_light_data l, vec3 p, vec3 n, float spec_power) {
  vec4 reach = dst_light_reach(int(l.direction_kind.w + 0.5f), l.position_range.xyz, l.direction_kind.xyz,
                               l.position_range.w, l.colour_cos_outer.w, l.cos_inner.x, p);
  vec3 light = l.colour_cos_outer.xyz * reach.w;
#ifdef DST_SHADOWS
  if (l.cos_inner.y > 0.5f) light = dst_shadowed_surface(light, p, n, l);
#endif
  dst_light_sample s = dst_phong(n, reach.xyz, normalize(frame.camera_position.xyz - p), spec_power, light);
#ifndef DST_RGB_SPECULAR
  s.specular = dst_decode_white_specular(dst_encode_white_specular(s.specular));
#endif
  return s;
}

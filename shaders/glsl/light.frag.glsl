// The light pass (thesis 3.2): additive blending, each pixel lit as the surface its G-buffer row holds.
// Spot lights may look up their shadow map: plain, or transparent by Eq. 3.1-3.2.
layout(location = 0) flat in uint light_id;

vec3 dst_world_position(ivec2 pixel, float depth) {
  vec2 ndc = vec2((float(pixel.x) + 0.5f) / float(frame.size.x) * 2.0f - 1.0f,
                  1.0f - (float(pixel.y) + 0.5f) / float(frame.size.y) * 2.0f);
  vec4 h = frame.inv_view_proj * vec4(ndc, depth, 1.0f);
  return h.xyz / h.w;
}

#if defined(DST_OPAQUE_SHADOWS) || defined(DST_TRANSPARENT_SHADOWS)
vec3 dst_shadowed(vec3 light, vec3 world, dst_light_data l) {
  vec4 h = l.shadow_view_proj * vec4(world, 1.0f);
  if (!(h.w > 0.0f)) return light;
  vec3 ndc = h.xyz / h.w;
  ivec2 size = frame.size.zw;
  ivec2 texel = ivec2(floor(vec2(ndc.x * 0.5f + 0.5f, 0.5f - ndc.y * 0.5f) * vec2(size)));
  if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, size))) return light;
#ifdef DST_TRANSPARENT_SHADOWS
  ivec2 other = dst_interlace_partner(texel, size);
  dst_surface a = dst_shadow_read(texel), b = dst_shadow_read(other);
  return dst_transparent_shadow(light, ndc.z, frame.params.y, a.depth, vec4(a.diffuse, a.alpha), b.depth,
                                vec4(b.diffuse, b.alpha));
#else
  return dst_opaque_shadow(light, ndc.z, frame.params.y, dst_shadow_read(texel).depth);
#endif
}
#endif

void main() {
  ivec2 pixel = dst_pixel();
  dst_surface s = dst_gbuffer_read(pixel);
  if (s.depth >= 1.0f) discard;  // nothing was drawn here
  dst_light_data l = lights[light_id];
  vec3 p = dst_world_position(pixel, s.depth);
  vec3 light = l.colour_cos_outer.xyz;
  vec3 to_light = -l.direction_kind.xyz;
  float kind = l.direction_kind.w;
  if (kind > 0.5f) {
    vec3 d = l.position_range.xyz - p;
    float distance = length(d);
    to_light = d / max(distance, 1e-6f);
    light *= dst_attenuation(distance, l.position_range.w);
    if (kind > 1.5f) light *= dst_spot_falloff(dot(-to_light, l.direction_kind.xyz), l.colour_cos_outer.w, l.cos_inner.x);
  }
#if defined(DST_OPAQUE_SHADOWS) || defined(DST_TRANSPARENT_SHADOWS)
  if (l.cos_inner.y > 0.5f) light = dst_shadowed(light, p, l);
#endif
  dst_light_sample result = dst_phong(s.normal, to_light, normalize(frame.camera_position.xyz - p), s.spec_power, light);
  dst_light_write(result);
}

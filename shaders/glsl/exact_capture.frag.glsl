// The exact reference's capture (technique reference): every transparent fragment of the scene's surfaces
// and hair in front of the opaque surfaces, shaded fully as it is drawn, into its pixel's list (lists.glsl).
// Glass is lit by every light as the light and compose passes light a surface (dst_light_at_point, each
// shadowed light's map read from its layer, shadow_layers.glsl), hair as the k-buffer's core (Eq. 2 with
// Eq. 1). A fragment that finds the pool used up goes to the tail targets, out of order, and is counted.
layout(location = 0) in vec3 world_normal;  // the strand's tangent, for hair
layout(location = 1) flat in uint surface_material;
layout(location = 0) out vec4 tail;           // premultiplied colour and alpha, added
layout(location = 1) out float optical_depth;  // -ln(1 - alpha), added

// The layer of light i's shadow map: the shadowed lights before it.
int dst_layer_of(int i) {
  int layer = 0;
  for (int k = 0; k < i; ++k)
    if (lights[k].cos_inner.y > 0.5f) ++layer;
  return layer;
}

// Surface s at `world`, lit by every light and the ambient light.
vec3 dst_lit_surface(dst_surface s, vec3 world) {
  dst_light_sample sum = dst_light_sample_zero();
  for (int i = 0; i < frame.counts.x; ++i) {
#ifdef DST_SHADOWS
    dst_shadow_layer = dst_layer_of(i);
#endif
    dst_light_sample l = dst_light_at_point(lights[i], world, s.normal, s.spec_power);
    sum.light += l.light;
    sum.specular += l.specular;
  }
  return dst_shade(s, sum, frame.ambient.xyz);
}

void main() {
  dst_material_data m = dst_material(surface_material);
  ivec2 p = dst_pixel();
  vec3 world = dst_world_position(p, gl_FragCoord.z);
  vec4 shaded;
  if (m.specular.w > 0.5f) {
    float alpha = m.diffuse_alpha.w;
    if (alpha < 1.0f / 255.0f || gl_FragCoord.z >= dst_gbuffer_read(p).depth) discard;
#ifdef DST_SHADOWS
    if (frame.params.z >= 0.0f) dst_shadow_layer = dst_layer_of(int(frame.params.z + 0.5f));
#endif
    shaded = vec4(dst_hair_lit(world, normalize(world_normal), vec4(m.diffuse_alpha.xyz, alpha), true), alpha);
  } else {
    dst_surface s = dst_material_surface(m, world_normal);  // before any discard: textures take derivatives
    if (!dst_transparent(s.alpha) || gl_FragCoord.z >= dst_gbuffer_read(p).depth) discard;
    shaded = vec4(dst_lit_surface(s, world), s.alpha);
  }
  tail = dst_push_shaded(p, gl_FragCoord.z, shaded, optical_depth);
}

// Where the single-layer interlaced G-buffer keeps the layer behind (or in front of) a pixel: on the
// pixel's interlace partner, in the same G-buffer and light buffer. With DST_RECONSTRUCT, the partner's
// sample averaged with the other layer's samples around the pixel that show the same surface
// (dst_layer_similarity and dst_reconstruct, interlace.hpp).
#ifdef DST_RECONSTRUCT
// The other layer's samples around `pixel` besides its partner (up to three: the 4-neighbours the
// predicate puts in the other layer), and how surely each shows the partner's surface.
void dst_other_around(ivec2 pixel, out ivec2 at[3], out vec3 weights) {
  ivec2 size = frame.size.xy;
  ivec2 partner = dst_interlace_partner(pixel, size);
  dst_surface p = dst_gbuffer_read(partner);
  bool mine = dst_interlace_keep(pixel, size);
  ivec2 around[4] = ivec2[](ivec2(0, -1), ivec2(0, 1), ivec2(-1, 0), ivec2(1, 0));
  at[0] = partner;
  at[1] = partner;
  at[2] = partner;
  weights = vec3(0.0f);
  int n = 0;
  for (int i = 0; i < 4; ++i) {
    ivec2 q = pixel + around[i];
    if (n == 3 || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)) || q == partner ||
        dst_interlace_keep(q, size) == mine)
      continue;
    dst_surface s = dst_gbuffer_read(q);
    at[n] = q;
    weights[n] = dst_layer_similarity(p.depth, p.normal, p.alpha, s.depth, s.normal, s.alpha);
    ++n;
  }
}

dst_surface dst_other(ivec2 pixel) {
  ivec2 at[3];
  vec3 w;
  dst_other_around(pixel, at, w);
  dst_surface p = dst_gbuffer_read(dst_interlace_partner(pixel, frame.size.xy));
  dst_surface a = dst_gbuffer_read(at[0]), b = dst_gbuffer_read(at[1]), c = dst_gbuffer_read(at[2]);
  dst_surface r = p;
  vec4 colour = dst_reconstruct(vec4(p.diffuse, p.alpha), vec4(a.diffuse, a.alpha), vec4(b.diffuse, b.alpha),
                                vec4(c.diffuse, c.alpha), w);
  vec4 shape = dst_reconstruct(vec4(p.normal, p.depth), vec4(a.normal, a.depth), vec4(b.normal, b.depth),
                               vec4(c.normal, c.depth), w);
  vec4 shine = dst_reconstruct(vec4(p.spec_intensity, p.spec_power, 0.0f, 0.0f), vec4(a.spec_intensity, a.spec_power, 0.0f, 0.0f),
                               vec4(b.spec_intensity, b.spec_power, 0.0f, 0.0f), vec4(c.spec_intensity, c.spec_power, 0.0f, 0.0f), w);
  r.diffuse = colour.xyz;
  r.alpha = colour.w;
  r.normal = dot(shape.xyz, shape.xyz) > 0.0f ? normalize(shape.xyz) : p.normal;
  r.depth = shape.w;
  r.spec_intensity = shine.x;
  r.spec_power = shine.y;
  return r;
}

dst_light_sample dst_other_light(ivec2 pixel) {
  ivec2 at[3];
  vec3 w;
  dst_other_around(pixel, at, w);
  dst_light_sample p = dst_light_read(dst_interlace_partner(pixel, frame.size.xy));
  dst_light_sample a = dst_light_read(at[0]), b = dst_light_read(at[1]), c = dst_light_read(at[2]);
  dst_light_sample r;
  r.light = dst_reconstruct(vec4(p.light, 0.0f), vec4(a.light, 0.0f), vec4(b.light, 0.0f), vec4(c.light, 0.0f), w).xyz;
  r.specular = dst_reconstruct(vec4(p.specular, 0.0f), vec4(a.specular, 0.0f), vec4(b.specular, 0.0f), vec4(c.specular, 0.0f), w).xyz;
  return r;
}
#else
dst_surface dst_other(ivec2 pixel) { return dst_gbuffer_read(dst_interlace_partner(pixel, frame.size.xy)); }
dst_light_sample dst_other_light(ivec2 pixel) { return dst_light_read(dst_interlace_partner(pixel, frame.size.xy)); }
#endif

// Edge-detect anti-aliasing from depth and normals (S3): each of the four neighbours weighs by how far its
// surface turns from or stands off the pixel's (dst_edge_weight: x per unit of 1 - cos, y per relative
// distance) times z, and the pixel becomes the weighted average with itself at weight 1. With DST_AA_INTERLACE the
// surfaces compared are those in front: where a pixel's row pair holds glass (the interlace predicate's
// partner has the lower alpha), the glass.
struct dst_front {
  vec3 normal;
  float distance;
};

dst_front dst_front_at(ivec2 p) {
  p = dst_post_clamp(p);
  dst_surface s = dst_gbuffer_read(p);
#ifdef DST_AA_INTERLACE
  dst_surface o = dst_gbuffer_read(dst_interlace_partner(p, frame.size.xy));
  if (o.alpha < s.alpha) s = o;
#endif
  return dst_front(s.normal, dst_post_distance(p, s.depth));
}

void main() {
  ivec2 p = dst_pixel();
  dst_front c = dst_front_at(p);
  vec4 sum = dst_post_fetch0(p);
  float total = 1.0f;
  ivec2 around[4] = ivec2[](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
  for (int i = 0; i < 4; ++i) {
    dst_front n = dst_front_at(p + around[i]);
    float w = post.params.z * dst_edge_weight(c.normal, n.normal, c.distance, n.distance, post.params.x, post.params.y);
    sum += w * dst_post_fetch0(p + around[i]);
    total += w;
  }
  dst_post_colour = sum / total;
}

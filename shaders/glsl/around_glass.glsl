// Where a pixel's glass and the opaque surface behind it lie, as window depths (x: the glass, -1 where the
// pixel shows none; y: the opaque surface), for the passes that draw hair and particles around the glass
// (DST_AROUND_GLASS): from the pixel and its interlace partner, paired as the compose pass pairs them, or
// from peeling's two layers (DST_PEELED). Without DST_AROUND_GLASS: no glass, and the G-buffer's depth.
// dst_behind_glass: whether a fragment at window depth `depth` lies behind glass at `glass` (always, without
// DST_AROUND_GLASS: a constant the compiler folds, so the passes pay nothing for the split).
#ifdef DST_AROUND_GLASS
bool dst_behind_glass(float depth, float glass) { return depth > glass; }
#ifdef DST_PEELED
vec2 dst_glass_and_opaque(ivec2 p) {
  dst_surface a = dst_gbuffer_read(p);
  if (!dst_transparent(a.alpha)) return vec2(-1.0f, a.depth);
  return vec2(a.depth, dst_gbuffer2_read(p).depth);
}
#else
vec2 dst_glass_and_opaque(ivec2 p) {
  dst_surface a = dst_gbuffer_read(p), b = dst_gbuffer_read(dst_gbuffer_interlace_partner(p, frame.size.xy));
  if (!dst_transparent(a.alpha) && !dst_transparent(b.alpha)) return vec2(-1.0f, a.depth);
  return a.alpha <= b.alpha ? vec2(a.depth, b.depth) : vec2(b.depth, a.depth);
}
#endif
#else
bool dst_behind_glass(float depth, float glass) { return true; }
vec2 dst_glass_and_opaque(ivec2 p) { return vec2(-1.0f, dst_gbuffer_read(p).depth); }
#endif

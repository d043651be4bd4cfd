// Where the single-layer interlaced G-buffer keeps the layer behind (or in front of) a pixel: on the
// pixel's interlace partner, in the same G-buffer and light buffer. With DST_RECONSTRUCT, the partner's
// sample averaged with the other layer's samples around the pixel that show the same surface
// (dst_layer_similarity and dst_reconstruct, interlace.hpp). With DST_TEMPORAL, the previous frame's sample
// (the second G-buffer and light buffer) where it shows the layer this pixel misses.
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

void dst_spatial_layer(ivec2 pixel, out dst_surface r, out dst_light_sample light) {
  ivec2 at[3];
  vec3 w;
  dst_other_around(pixel, at, w);
  ivec2 partner = dst_interlace_partner(pixel, frame.size.xy);
  dst_surface p = dst_gbuffer_read(partner);
  dst_surface a = dst_gbuffer_read(at[0]), b = dst_gbuffer_read(at[1]), c = dst_gbuffer_read(at[2]);
  r = p;
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
  dst_light_sample lp = dst_light_read(partner);
  dst_light_sample la = dst_light_read(at[0]), lb = dst_light_read(at[1]), lc = dst_light_read(at[2]);
  light.light = dst_reconstruct(vec4(lp.light, 0.0f), vec4(la.light, 0.0f), vec4(lb.light, 0.0f), vec4(lc.light, 0.0f), w).xyz;
  light.specular =
      dst_reconstruct(vec4(lp.specular, 0.0f), vec4(la.specular, 0.0f), vec4(lb.specular, 0.0f), vec4(lc.specular, 0.0f), w).xyz;
}
#else
void dst_spatial_layer(ivec2 pixel, out dst_surface r, out dst_light_sample light) {
  ivec2 partner = dst_interlace_partner(pixel, frame.size.xy);
  r = dst_gbuffer_read(partner);
  light = dst_light_read(partner);
}
#endif

#ifdef DST_TEMPORAL
// The interlace phase alternates, so where the camera stood still the previous frame stored at this pixel
// the layer this frame does not. Where the other layer of a pixel `here` comes from: 0, the spatial
// reconstruction; 1, the previous frame's sample (interpolated with its neighbours: dst_history_between),
// or where it has none, this frame's samples on either side along the interlace (dst_beside); 2, nowhere:
// no glass lies in front of this pixel's opaque surface, which is then its own other layer.
// - A pixel that keeps glass this frame and holds an opaque surface has no glass in front of it, nor has
//   one whose other layer's samples beside it show no glass.
// - The previous frame's sample is taken where it lies on this pixel's ray now (within a pixel) and is the
//   layer missing here: glass in front of this pixel's opaque surface, where the other layer's samples
//   beside the pixel show glass (so glass that moved away leaves nothing), or the opaque surface behind
//   this pixel's glass. The previous frame's pixel is found by reprojecting the depth of the other layer's
//   samples on either side along the interlace (at an edge, one of them shows the pixel's surface), and the
//   sample nearer the ray is taken. Where both of those samples can be the missing layer, its colour is
//   held near theirs (dst_history_box): a sliver one pixel thin that a moving camera's new sample grid
//   steps over is not carried on.
// - Where the camera has not moved, a pixel that kept glass in the previous frame and held this same
//   opaque surface had none in front of it (glass that moved in shows from the next frame); and glass it
//   kept with none two pixels either side along the interlace is a sliver one pixel thin, which this frame
//   cannot see beside the pixel (a sliver that moved away shows for one frame more).
//
// Whether the camera stood still (frame.interlace.w) is known before the frame is recorded, so the renderer
// draws a variant of the compose pass for each case, DST_STILL_CAMERA on still frames: a rasteriser that runs
// both sides of a branch under a mask (llvmpipe, lavapipe) then pays for neither side's samples on the other.

// Whether `s` can be the layer `here` misses: glass in front of it, or the opaque surface behind its glass.
bool dst_missing_layer(dst_surface s, dst_surface here, bool glass) {
  return dst_transparent(s.alpha) == glass && (glass ? s.depth < here.depth : s.depth > here.depth);
}

#ifdef DST_STILL_CAMERA
bool dst_lone_glass(ivec2 pixel, ivec2 step, dst_surface here) {
  ivec2 size = frame.size.xy;
  dst_surface h = dst_gbuffer2_read(pixel);
  ivec2 a = clamp(pixel + 2 * step, ivec2(0), size - 1), b = clamp(pixel - 2 * step, ivec2(0), size - 1);
  return dst_transparent(h.alpha) && h.depth < here.depth && !dst_transparent(dst_gbuffer2_read(a).alpha) &&
         !dst_transparent(dst_gbuffer2_read(b).alpha);
}

#else
// The previous frame's sample at `at`, its depth turned into this frame's, and where it lies now (window
// coordinates); false where it lies behind the camera now.
bool dst_history_read(ivec2 at, out dst_surface h, out vec2 now) {
  ivec2 size = frame.size.xy;
  h = dst_gbuffer2_read(at);
  vec4 p = frame.from_previous * vec4(dst_pixel_ndc(at, size), h.depth, 1.0f);
  now = vec2(0.0f);
  if (!(p.w > 0.0f)) return false;
  h.depth = p.z / p.w;
  now = dst_ndc_window(p.xy / p.w, size);
  return true;
}

// The previous frame's sample of the layer `glass` asks for, nearest to where the surface at `depth` on
// `pixel`'s ray lay then: the nearest pixel, or when that kept the other layer, its neighbour along the
// interlace `step` on the point's side. The sample's depth `h` is its depth now; `offset` says where it
// lies (dst_history_shares: x across the interlace then, y along it now); the result is how far (in
// pixels) the sample lies from the pixel's ray now, 2 where there is none.
float dst_history_sample(ivec2 pixel, float depth, bool glass, ivec2 step, out ivec2 at, out dst_surface h,
                         out vec2 offset) {
  ivec2 size = frame.size.xy;
  at = pixel;
  h = dst_surface_zero();
  offset = vec2(0.0f);
  vec4 before = frame.to_previous * vec4(dst_pixel_ndc(pixel, size), depth, 1.0f);
  if (!(before.w > 0.0f)) return 2.0f;
  vec2 w = dst_ndc_window(before.xy / before.w, size);
  if (any(lessThan(w, vec2(0.0f))) || any(greaterThanEqual(w, vec2(size)))) return 2.0f;
  at = ivec2(w);
  if (dst_transparent(dst_gbuffer2_read(at).alpha) != glass)
    at = clamp(at + (dot(w - vec2(at) - 0.5f, vec2(step)) >= 0.0f ? step : -step), ivec2(0), size - 1);
  vec2 now;
  if (!dst_history_read(at, h, now) || dst_transparent(h.alpha) != glass) return 2.0f;
  offset = vec2(dot(w - vec2(at) - 0.5f, vec2(step.yx)), dot(now - vec2(pixel) - 0.5f, vec2(step)));
  return distance(now, vec2(pixel) + 0.5f);
}

// The history sample `h` (with its light) interpolated with its neighbour across the interlace in the
// previous frame and with this frame's sample of the same layer on the pixel's other side along it.
void dst_history_between(ivec2 pixel, ivec2 at, ivec2 step, vec2 offset, inout dst_surface h, inout dst_light_sample light) {
  ivec2 size = frame.size.xy;
  ivec2 across = clamp(at + (offset.x >= 0.0f ? step.yx : -step.yx), ivec2(0), size - 1);
  ivec2 along = clamp(pixel - (offset.y >= 0.0f ? step : -step), ivec2(0), size - 1);
  dst_surface a, b = dst_gbuffer_read(along);
  vec2 now;
  float same_a = dst_history_read(across, a, now) ? dst_layer_similarity(h.depth, h.normal, h.alpha, a.depth, a.normal, a.alpha) : 0.0f;
  vec2 share = dst_history_shares(offset, vec2(same_a, dst_layer_similarity(h.depth, h.normal, h.alpha, b.depth, b.normal, b.alpha)));
  if (share.x > 0.0f) {
    h = dst_surface_mix(h, a, share.x);
    light = dst_light_mix(light, dst_light2_read(across), share.x);
  }
  if (share.y > 0.0f) {
    h = dst_surface_mix(h, b, share.y);
    light = dst_light_mix(light, dst_light_read(along), share.y);
  }
}

// The layer `here` misses from this frame's samples `p` (at the partner) and `q` (at `beyond`, on the
// pixel's other side along the interlace), where the previous frame has none: their mean where both can be
// it and show one surface (the linear interpolation at the pixel), else the one that can, the partner
// first; false where neither can. At the edge of a pane the partner may lie outside it while the pixel's
// other neighbour shows the glass, so the partner alone (the thesis's pairing) would lose the glass there.
bool dst_beside(dst_surface here, bool glass, ivec2 partner, ivec2 beyond, dst_surface p, dst_surface q,
                out dst_surface h, out dst_light_sample light) {
  bool p_can = dst_missing_layer(p, here, glass), q_can = dst_missing_layer(q, here, glass);
  float share = p_can ? 0.5f * dst_layer_similarity(p.depth, p.normal, p.alpha, q.depth, q.normal, q.alpha) : 1.0f;
  if (!q_can) share = 0.0f;
  h = dst_surface_mix(p, q, share);
  light = dst_light_mix(dst_light_read(partner), dst_light_read(beyond), share);
  return p_can || q_can;
}

// The history sample `h` (with its light) held near this frame's samples `p` and `q` of the same layer at
// `partner` and `beyond`, where both can be the layer `here` misses.
void dst_history_hold(dst_surface here, bool glass, ivec2 partner, ivec2 beyond, dst_surface p, dst_surface q,
                      inout dst_surface h, inout dst_light_sample light) {
  if (!dst_missing_layer(p, here, glass) || !dst_missing_layer(q, here, glass)) return;
  dst_light_sample lp = dst_light_read(partner), lq = dst_light_read(beyond);
  h.diffuse = dst_history_box(h.diffuse, p.diffuse, q.diffuse);
  light.light = dst_history_box(light.light, lp.light, lq.light);
  light.specular = dst_history_box(light.specular, lp.specular, lq.specular);
}

#endif

// Where the other layer of `pixel` comes from (see above), with the sample `h` and its light.
int dst_history_at(ivec2 pixel, dst_surface here, out dst_surface h, out dst_light_sample light) {
  h = here;
  light = dst_light_read(pixel);
  ivec2 size = frame.size.xy;
  bool want_glass = !dst_transparent(here.alpha);
  if (want_glass && dst_interlace_keep(pixel + frame.interlace.xy, size)) return 2;
  if (frame.interlace.z == 0) return 0;
  ivec2 partner = dst_interlace_partner(pixel, size);
  ivec2 beyond = clamp(2 * pixel - partner, ivec2(0), size - 1);
  dst_surface p = dst_gbuffer_read(partner), q = dst_gbuffer_read(beyond);
  // No glass beside this opaque surface: nothing in front of it (whatever the other layer, the compose
  // shades the surface alone), unless the previous frame kept a sliver of glass here.
#ifdef DST_STILL_CAMERA
  if (want_glass && !dst_transparent(p.alpha) && !dst_transparent(q.alpha) && !dst_lone_glass(pixel, pixel - partner, here)) return 2;
  h = dst_gbuffer2_read(pixel);
  light = dst_light2_read(pixel);
  if (dst_transparent(h.alpha) == want_glass) return dst_missing_layer(h, here, want_glass) ? 1 : 0;
  return want_glass && abs(h.depth - here.depth) <= 1e-5f * here.depth ? 2 : 0;
#else
  if (want_glass && !dst_transparent(p.alpha) && !dst_transparent(q.alpha)) return 2;
  ivec2 step = abs(pixel - partner), at, at_q;
  dst_surface h_q;
  vec2 offset, offset_q;
  float off = dst_history_sample(pixel, p.depth, want_glass, step, at, h, offset);
  float off_q = dst_history_sample(pixel, q.depth, want_glass, step, at_q, h_q, offset_q);
  if (off_q < off) {
    off = off_q;
    at = at_q;
    h = h_q;
    offset = offset_q;
  }
  if (!(off < 1.0f) || !dst_missing_layer(h, here, want_glass)) return dst_beside(here, want_glass, partner, beyond, p, q, h, light) ? 1 : 0;
  light = dst_light2_read(at);
  dst_history_between(pixel, at, step, offset, h, light);
  dst_history_hold(here, want_glass, partner, beyond, p, q, h, light);
  return 1;
#endif
}

void dst_other_layer(ivec2 pixel, dst_surface here, out dst_surface s, out dst_light_sample light) {
  if (dst_history_at(pixel, here, s, light) == 0) dst_spatial_layer(pixel, s, light);
}
#else
void dst_other_layer(ivec2 pixel, dst_surface here, out dst_surface s, out dst_light_sample light) {
  dst_spatial_layer(pixel, s, light);
}
#endif

// The forward blend pass (thesis 4.1.3/4.1.4): de-interlaces the lit image and refracts. With
// DST_FORWARD_DEPTH a moved sample in front of the glass is rejected by depth, as in the compose pass;
// without it, by the alpha found while de-interlacing (Sousa's mask): the moved sample is taken only
// where glass covers it, which lets a foreground object over glass leak in and rejects valid background
// beside the glass (the two errors of Figure 4.7).
layout(location = 0) out vec4 colour;
layout(binding = DST_SLOT_FORWARD_LIT) uniform sampler2D dst_forward_colour;
layout(binding = DST_SLOT_FORWARD_LIT + 1) uniform sampler2D dst_forward_normal;
#ifdef DST_FORWARD_DEPTH
layout(binding = DST_SLOT_FORWARD_LIT + 2) uniform sampler2D dst_forward_depth;
#endif

void main() {
  ivec2 size = frame.size.xy;
  ivec2 p = dst_pixel(), q = dst_interlace_partner(p, size);
  vec4 a = texelFetch(dst_forward_colour, p, 0), b = texelFetch(dst_forward_colour, q, 0);
  if (!dst_transparent(a.w) && !dst_transparent(b.w)) {
    colour = vec4(a.xyz, 1.0f);
    return;
  }
  bool a_transparent = a.w <= b.w;
  ivec2 tp = a_transparent ? p : q;
  vec4 t = a_transparent ? a : b;
  vec4 o = a_transparent ? b : a;
  vec3 view_normal = mat3(frame.view) * dst_decode_normal(texelFetch(dst_forward_normal, tp, 0).xyz);
  ivec2 moved = dst_refraction_pixel(p, size, view_normal, frame.params.x);
  ivec2 moved_partner = dst_interlace_partner(moved, size);
  vec4 r = texelFetch(dst_forward_colour, moved, 0), r2 = texelFetch(dst_forward_colour, moved_partner, 0);
  float alpha_moved = r.w, alpha_partner = r2.w;
#ifdef DST_FORWARD_DEPTH
  bool accept = dst_refraction_source(texelFetch(dst_forward_depth, tp, 0).x, alpha_moved, texelFetch(dst_forward_depth, moved, 0).x,
                                      alpha_partner, texelFetch(dst_forward_depth, moved_partner, 0).x) != 0;
#else
  bool accept = dst_refraction_accepted_by_mask(alpha_moved, alpha_partner);
#endif
  if (accept) o = dst_transparent(r.w) ? r2 : r;
  colour = vec4(dst_blend(o.xyz, t.xyz, t.w), 1.0f);
}

// The G-buffer pass (thesis 3.1.1): depth test and write on, blending off. With DST_TRANSPARENCY a
// transparent fragment is kept only where the interlace predicate allows; transparent materials are
// double-sided, their normal turned to face the viewer. With DST_PEEL it is the second layer of deferred
// depth peeling (4.1.2): only opaque fragments behind the first layer's depth. With DST_OPAQUE_ONLY (the
// exact reference, whose lists take every transparent fragment) only opaque fragments.
layout(location = 0) in vec3 world_normal;
layout(location = 1) flat in uint surface_material;
#ifdef DST_PEEL
layout(binding = DST_SLOT_PEEL_DEPTH) uniform sampler2D dst_peel_depth;
#endif

void main() {
  dst_surface s = dst_material_surface(dst_material(surface_material), world_normal);
#ifdef DST_PEEL
  if (dst_transparent(s.alpha) || gl_FragCoord.z <= texelFetch(dst_peel_depth, dst_pixel(), 0).x) discard;
#endif
#ifdef DST_OPAQUE_ONLY
  if (dst_transparent(s.alpha)) discard;
#endif
#ifdef DST_TRANSPARENCY
  // frame.interlace.xy: this frame's phase (temporal interlacing alternates the rows that keep glass).
  if (dst_transparent(s.alpha) && !dst_interlace_keep(dst_pixel() + frame.interlace.xy, frame.size.xy)) discard;
#endif
  dst_gbuffer_write(s);
}

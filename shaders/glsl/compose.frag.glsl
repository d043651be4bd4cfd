// The compose pass (thesis 3.3). Without transparency, plain deferred shading of the one layer. With
// DST_TRANSPARENCY, de-interlacing and the blend of Eq. 3.3 with specular and ambient light; with
// DST_REFRACTION also refraction with the partner-row fallback and depth rejection. The technique says
// where the other layer of a pixel lives (interlaced.glsl, peeled.glsl): dst_other_layer.
layout(location = 0) out vec4 colour;

void main() {
  ivec2 p = dst_pixel();
  dst_surface a = dst_gbuffer_read(p);
  dst_light_sample light_a = dst_light_read(p);
  vec3 ambient = frame.ambient.xyz;
#ifdef DST_TRANSPARENCY
  dst_surface b;
  dst_light_sample light_b;
  dst_other_layer(p, a, b, light_b);
  if (dst_transparent(a.alpha) || dst_transparent(b.alpha)) {
    bool a_transparent = a.alpha <= b.alpha;
    dst_surface t = a_transparent ? a : b;
    dst_light_sample light_t = a_transparent ? light_a : light_b;
    dst_surface o = a_transparent ? b : a;
    dst_light_sample light_o = a_transparent ? light_b : light_a;
#ifdef DST_REFRACTION
    // The sample moved by the glass's screen-space normal, or the layer behind it when it holds glass
    // too; a sample in front of the glass would leak into it, so the background stays then.
    ivec2 moved = dst_refraction_pixel(p, frame.size.xy, mat3(frame.view) * t.normal, frame.params.x);
    dst_surface r = dst_gbuffer_read(moved), r2 = r;
    dst_light_sample light_r2 = dst_light_sample_zero();
    if (dst_transparent(r.alpha)) dst_other_layer(moved, r, r2, light_r2);  // the other layer only where it is needed
    int from = dst_refraction_source(t.depth, r.alpha, r.depth, r2.alpha, r2.depth);
    if (from != 0) {
      o = from == 1 ? r : r2;
      light_o = from == 1 ? dst_light_read(moved) : light_r2;
    }
#endif
    colour = vec4(dst_compose(o, light_o, t, light_t, ambient), 1.0f);
    return;
  }
#endif
  colour = vec4(dst_shade(a, light_a, ambient), 1.0f);  // empty pixels are cleared to black
}

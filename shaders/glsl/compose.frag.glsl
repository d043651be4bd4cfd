// The compose pass (thesis 3.3). Without transparency, plain deferred shading of the one layer. With
// DST_TRANSPARENCY, de-interlacing and the blend of Eq. 3.3 with specular and ambient light; with
// DST_REFRACTION also refraction with the partner-row fallback and depth rejection. The technique says
// where the other layer of a pixel lives (interlaced.glsl, peeled.glsl): dst_other_layer. With
// DST_ROUGH_REFRACTION the refracted sample is blurred by the glass's roughness (refraction.hpp). With
// DST_AROUND_GLASS the hair and particles lie in depth order around the glass: what lies behind it is laid
// over the surface behind before the blend (refracted with it), what lies in front over the blend.
layout(location = 0) out vec4 colour;

#ifdef DST_AROUND_GLASS
layout(binding = DST_SLOT_GLASS_LAYERS) uniform sampler2D dst_glass_behind;
layout(binding = DST_SLOT_GLASS_LAYERS + 1) uniform sampler2D dst_glass_front;
// `lit`, what pixel q shows behind its glass, under the hair and particles that lie between the two.
vec3 dst_under_glass(ivec2 q, vec3 lit) {
  vec4 b = texelFetch(dst_glass_behind, q, 0);
  return b.xyz + lit * b.w;
}
// `c`, pixel p's colour up to its glass, under the hair and particles in front of the glass.
vec3 dst_over_glass(ivec2 p, vec3 c) {
  vec4 f = texelFetch(dst_glass_front, p, 0);
  return f.xyz + c * f.w;
}
#else
vec3 dst_under_glass(ivec2 q, vec3 lit) { return lit; }
vec3 dst_over_glass(ivec2 p, vec3 c) { return c; }
#endif

#ifdef DST_REFRACTION
// What glass t shows at pixel q: q's sample, or the layer behind it where q holds glass too; true where it
// took it. A sample in front of the glass would leak into it, so o and light_o (the glass's own
// background) stay then.
bool dst_refracted(ivec2 q, dst_surface t, inout dst_surface o, inout dst_light_sample light_o) {
  dst_surface r = dst_gbuffer_read(q), r2 = r;
  dst_light_sample light_r2 = dst_light_sample_zero();
  if (dst_transparent(r.alpha)) dst_other_layer(q, r, r2, light_r2);  // the other layer only where it is needed
  int from = dst_refraction_source(t.depth, r.alpha, r.depth, r2.alpha, r2.depth);
  if (from != 0) {
    o = from == 1 ? r : r2;
    light_o = from == 1 ? dst_light_read(q) : light_r2;
  }
  return from != 0;
}
#endif

#ifdef DST_ROUGH_REFRACTION
// The view depth of what pixel q shows at window depth `depth`.
float dst_view_depth(ivec2 q, float depth) { return -(frame.view * vec4(dst_world_position(q, depth), 1.0f)).z; }

// The lit colour glass t shows around pixel `moved`, whose sample lit is `lit`, blurred by t's roughness;
// `behind` is the glass's own background, which a tap that would leak keeps.
vec3 dst_rough_refracted(ivec2 p, ivec2 moved, vec3 lit, dst_surface t, dst_surface o, dst_surface behind,
                         dst_light_sample light_behind, vec3 ambient) {
  float radius = dst_refraction_blur_pixels(dst_roughness_of_phong_power(t.spec_power), dst_view_depth(p, t.depth),
                                            dst_view_depth(moved, o.depth), frame.camera_position.w, 0.0625f * float(frame.size.y));
  if (radius < 0.5f) return lit;
  vec3 sum = lit * dst_refraction_blur_tap(0).z;
  for (int i = 1; i < 15; ++i) {
    vec3 tap = dst_refraction_blur_tap(i);
    ivec2 q = clamp(moved + ivec2(floor(vec2(tap.x, tap.y) * radius + 0.5f)), ivec2(0), frame.size.xy - 1);
    dst_surface s = behind;
    dst_light_sample light_s = light_behind;
    bool taken = dst_refracted(q, t, s, light_s);
    sum += dst_under_glass(taken ? q : p, dst_shade(s, light_s, ambient)) * tap.z;
  }
  return sum;
}
#endif

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
    ivec2 from = p;  // the pixel whose surface behind the glass the glass shows
#ifdef DST_REFRACTION
    // The sample moved by the glass's screen-space normal, or the layer behind it when it holds glass
    // too; a sample in front of the glass would leak into it, so the background stays then.
    ivec2 moved = dst_refraction_pixel(p, frame.size.xy, mat3(frame.view) * t.normal, frame.params.x);
#ifdef DST_ROUGH_REFRACTION
    dst_surface behind = o;
    dst_light_sample light_behind = light_o;
#endif
    if (dst_refracted(moved, t, o, light_o)) from = moved;
#endif
    vec3 lit_o = dst_under_glass(from, dst_shade(o, light_o, ambient));
#ifdef DST_ROUGH_REFRACTION
    lit_o = dst_rough_refracted(p, moved, lit_o, t, o, behind, light_behind, ambient);
#endif
    colour = vec4(dst_over_glass(p, dst_blend(lit_o, dst_shade(t, light_t, ambient), t.alpha)), 1.0f);
    return;
  }
#endif
  colour = vec4(dst_over_glass(p, dst_under_glass(p, dst_shade(a, light_a, ambient))), 1.0f);  // empty pixels are cleared to black
}

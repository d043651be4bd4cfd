// The compose pass (thesis 3.3): de-interlacing, refraction with the partner-row fallback and depth
// rejection, and the blend of Eq. 3.3 with specular and ambient light.
layout(location = 0) out vec4 colour;

void main() {
  ivec2 size = frame.size.xy;
  ivec2 p = dst_pixel(), q = dst_interlace_partner(p, size);
  dst_surface a = dst_gbuffer_read(p), b = dst_gbuffer_read(q);
  vec3 ambient = frame.ambient.xyz;
  if (a.alpha >= 1.0f && b.alpha >= 1.0f) {
    colour = vec4(dst_shade(a, dst_light_read(p), ambient), 1.0f);  // empty pixels are cleared to black
    return;
  }
  bool a_transparent = a.alpha <= b.alpha;
  dst_surface t = a_transparent ? a : b;
  dst_light_sample light_t = dst_light_read(a_transparent ? p : q);
  dst_surface o = a_transparent ? b : a;
  dst_light_sample light_o = dst_light_read(a_transparent ? q : p);
  // Refraction: the sample moved by the transparent surface's screen-space normal, or its partner when it
  // holds glass too; a sample in front of the glass would leak into it, so the background stays then.
  vec3 view_normal = mat3(frame.view) * t.normal;
  ivec2 moved = clamp(p + ivec2(round(dst_refraction_offset(view_normal, frame.params.x))), ivec2(0), size - 1);
  dst_surface r = dst_gbuffer_read(moved);
  if (r.alpha < 1.0f) {
    moved = dst_interlace_partner(moved, size);
    r = dst_gbuffer_read(moved);
  }
  if (r.alpha >= 1.0f && !dst_refraction_rejected(t.depth, r.depth)) {
    o = r;
    light_o = dst_light_read(moved);
  }
  colour = vec4(dst_compose(o, light_o, t, light_t, ambient), 1.0f);
}

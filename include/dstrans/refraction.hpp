// Screen-space refraction with depth rejection, and the compose blend (the thesis, 3.3, Eq. 3.3).
//
// The compose pass samples the G-buffer at the pixel and at its interlace partner; the lower-alpha
// sample is the transparent S_t, the other the background S_b. The screen-space xy of S_t's normal
// times a strength (in pixels) moves the sample to P; if P holds a transparent sample its partner,
// opaque by construction, is used: P_o. If S_t lies behind P_o, P_o is a foreground object that would
// leak into the glass, and S_b is used instead. Then
//   I_F = (C_o I_o)(1 - alpha_t) + (C_t I_t) alpha_t,
// where each term also receives the ambient light and its white specular (spec_intensity times the
// light buffer's specular).
//
//   glm::ivec2 moved = dstrans::shader::dst_refraction_pixel(pixel, size, view_normal, strength);
//   int from = dstrans::shader::dst_refraction_source(depth_t, alpha_moved, depth_moved, alpha_partner, depth_partner);
//   bool leak = dstrans::shader::dst_refraction_rejected(depth_t, depth_o);
//   glm::vec3 colour = dstrans::shader::dst_compose(opaque, light_o, transparent, light_t, ambient);
//   glm::vec3 same = dstrans::shader::dst_blend(lit_opaque, lit_transparent, alpha_t);   // colours already lit
//   float r = dstrans::shader::dst_roughness_of_phong_power(surface.spec_power);     // rough glass
//   float radius = dstrans::shader::dst_refraction_blur_pixels(r, z_glass, z_behind, focal, 32.0f);
//   glm::vec3 tap = dstrans::shader::dst_refraction_blur_tap(i);   // xy * radius: offset, z: weight
//   dstrans::glsl::add_refraction(src);   // GLSL: dst_refract(pixel, size, view_normal, strength), with
//                                          // pixels counting rows as src's dialect says (glsl::rows)
//
// Choices (each one of the project's tested hard cases): screen y grows downwards while view y grows upwards, so
// the offset's y is negated; the offset rounds to the nearest pixel, halves up (GLSL's round() may go
// either way); a sample pushed off the image is taken at its edge (clamped per axis), a NaN offset does
// not move it; equal depths are not rejected (a surface does not leak into itself); when the moved pixel
// and its partner both hold glass there is no opaque sample to refract and the background S_b stays
// (dst_refraction_source 0; 1 takes the moved pixel, 2 its partner); the cleared background (depth 1,
// black) behind glass is refracted like any opaque surface; strength 0 gives no offset, and the compose
// is then exactly the de-interlaced blend.
// The moved sample is taken when one of the moved pixel and its partner is opaque (alpha_moved,
// alpha_partner) and, by depth, it lies behind the glass; forward rendering without depth can only ask
// instead whether glass covers the moved pixel (the other of the two is transparent): Sousa's mask, which
// accepts a foreground object seen through other glass and rejects background beside the glass, the two
// errors of the thesis's Figure 4.7.
#pragma once

#include <string>

#include "detail/shared.hpp"
#include "glsl.hpp"
#include "interlace.hpp"
#include "surface.hpp"

DSTRANS_SHARED(dst_refraction,
DST_FN vec2 dst_refraction_offset(vec3 view_normal, float strength) {
  return vec2(view_normal.x, -view_normal.y) * strength;
}
DST_FN int dst_refraction_shift(int x, float offset, int extent) {
  if (extent < 1) return 0;
  float moved = float(x) + floor(offset + 0.5f);
  if (isnan(moved)) return x;
  if (moved >= float(extent - 1)) return extent - 1;
  return moved > 0.0f ? int(moved) : 0;
}
DST_FN ivec2 dst_refraction_pixel(ivec2 p, ivec2 size, vec3 view_normal, float strength) {
  vec2 o = dst_refraction_offset(view_normal, strength);
  return ivec2(dst_refraction_shift(p.x, o.x, size.x), dst_refraction_shift(p.y, o.y, size.y));
}
DST_FN bool dst_refraction_rejected(float depth_t, float depth_o) { return depth_t > depth_o; }
DST_FN int dst_refraction_source(float depth_t, float alpha_moved, float depth_moved, float alpha_partner,
                                 float depth_partner) {
  if (!dst_transparent(alpha_moved)) return dst_refraction_rejected(depth_t, depth_moved) ? 0 : 1;
  if (!dst_transparent(alpha_partner)) return dst_refraction_rejected(depth_t, depth_partner) ? 0 : 2;
  return 0;
}
DST_FN bool dst_refraction_accepted_by_mask(float alpha_moved, float alpha_partner) {
  return dst_transparent(alpha_moved) != dst_transparent(alpha_partner);
}
)

// Rough glass (options::rough_refraction): the refracted sample blurred by the glass's roughness. glTF's
// roughness r is stored as the Phong exponent 2 / r^4 - 2 within [1, 255] (the Blinn-Phong match of GGX's
// width), and glTF transmits through the roughness it reflects with, so the compose reads r back from the
// G-buffer's exponent: no byte more a pixel. An exponent of 255 (r up to 0.297, which 8 bits cannot tell
// apart) reads back as clear glass. The transmitted light leaves within GGX's width r^2 (radians) of the
// refracted ray, so it spreads over (z_b - z_t) tan(r^2) at a surface z_b behind glass at z_t (view
// depths), focal (z_b - z_t) tan(r^2) / z_b pixels across, focal being the projection's pixels per unit at
// unit depth. The spread is taken as at most 1 radian and the radius as at most `limit` pixels; a surface
// not behind the glass, a NaN or a limit not above 0 gives 0. The blur is a uniform disc of that radius in
// 15 taps: a centre, a ring of 6 at half the radius and a ring of 8 at the radius, each tap weighted by the
// area it stands for, and each ring symmetric about the x axis, so that rows counted from the top or from
// the bottom sample the same pixels.
DSTRANS_SHARED(dst_rough_refraction,
DST_FN float dst_phong_power_of_roughness(float r) {
  if (isnan(r)) return 255.0f;
  float r4 = r * r * r * r;
  if (r4 <= 2.0f / 257.0f) return 255.0f;
  float n = 2.0f / r4 - 2.0f;
  return n < 1.0f ? 1.0f : n;
}
DST_FN float dst_roughness_of_phong_power(float n) {
  if (isnan(n) || n >= 254.5f) return 0.0f;
  return pow(2.0f / (max(n, 0.0f) + 2.0f), 0.25f);
}
DST_FN float dst_refraction_blur_pixels(float roughness, float z_t, float z_b, float focal, float limit) {
  if (isnan(roughness) || isnan(limit) || limit <= 0.0f) return 0.0f;
  float spread = roughness * roughness;
  float px = focal * tan(spread < 1.0f ? spread : 1.0f) * (1.0f - z_t / z_b);
  if (isnan(px) || px <= 0.0f) return 0.0f;
  return px < limit ? px : limit;
}
DST_FN vec3 dst_refraction_blur_tap(int i) {
  if (i < 0 || i > 14) return vec3(0.0f);
  if (i == 0) return vec3(0.0f, 0.0f, 0.0625f);
  if (i <= 6) {
    float a = float(i - 1) * 1.04719755f;
    return vec3(0.5f * cos(a), 0.5f * sin(a), 0.5f / 6.0f);
  }
  float b = (float(i - 7) + 0.5f) * 0.785398163f;
  return vec3(cos(b), sin(b), 0.4375f / 8.0f);
}
)

DSTRANS_SHARED(dst_compose,
DST_FN vec3 dst_shade(dst_surface s, dst_light_sample l, vec3 ambient) {
  return s.diffuse * (l.light + ambient) + vec3(s.spec_intensity * l.specular);
}
DST_FN vec3 dst_blend(vec3 opaque, vec3 transparent, float alpha_t) {
  return opaque * (1.0f - alpha_t) + transparent * alpha_t;
}
DST_FN vec3 dst_compose(dst_surface o, dst_light_sample light_o, dst_surface t, dst_light_sample light_t, vec3 ambient) {
  return dst_blend(dst_shade(o, light_o, ambient), dst_shade(t, light_t, ambient), t.alpha);
}
)

namespace dstrans::glsl {

// Appends the refraction formulas and
//   ivec2 dst_refract(ivec2 pixel, ivec2 size, vec3 view_normal, float strength);
// dst_refraction_pixel for pixels that count rows as src.pixel_rows() says: from the bottom, the offset's
// y keeps the view normal's sign, since both grow upwards.
inline void add_refraction(source& src) {
  src.add_shared(text::dst_refraction);
  if (src.pixel_rows() == rows::from_top) {
    src.add("ivec2 dst_refract(ivec2 pixel, ivec2 size, vec3 view_normal, float strength) {\n"
            "  return dst_refraction_pixel(pixel, size, view_normal, strength);\n}\n",
            __FILE__, __LINE__);
    return;
  }
  src.add_shared(text::dst_flip_rows);
  src.add("ivec2 dst_refract(ivec2 pixel, ivec2 size, vec3 view_normal, float strength) {  // pixels from the bottom row\n"
          "  return dst_flip_rows(dst_refraction_pixel(dst_flip_rows(pixel, size), size, view_normal, strength), size);\n}\n",
          __FILE__, __LINE__);
}

}  // namespace dstrans::glsl

// Many transparent layers: per-pixel lists of shading inputs, the k nearest fragments
// shaded fully and blended in order (the core), the rest shaded cheaply and blended out of order (the
// tail); and the hair shading and shadow the technique was measured with.
//
//   glm::uvec4 node(glm::floatBitsToUint(depth), dst_pack_tangent(t), dst_pack_colour(glm::vec4(c, alpha)), next);
//   glm::vec3 full = dstrans::shader::dst_hair_full(t, l, v, colour, light, visibility);    // Eq. 2
//   glm::vec3 cheap = dstrans::shader::dst_hair_cheap(t, l, colour, light, visibility);     // R_d only
//   glm::vec4 tail = dstrans::shader::dst_tail_add(tail, glm::vec4(cheap, alpha));          // any order
//   glm::vec3 all = dstrans::shader::dst_hair_cheap_mean(diag, off, l, sum, light, visibility);  // or at once
//   glm::vec3 behind = dstrans::shader::dst_tail_over(background, tail, transmittance);    // then the core
//
// Choices, each tested:
// - a node is 16 bytes: depth (float bits), the tangent octahedrally encoded in two 16-bit snorms, colour
//   and alpha in RGBA8, the next node's index (0xffffffff ends a list);
// - Eq. 2 uses Kajiya-Kay: diffuse sin(T, L), and two specular lobes (R and TRT) along tangents shifted
//   towards the viewer-facing normal of the strand (shift -0.1 and +0.1, exponents 80 and 20, TRT tinted by
//   the hair's colour) with the half-vector form of Scheuermann (2004); the cheap shader is the diffuse term,
//   and the resolve runs it once for a pixel's whole tail (dst_hair_cheap_mean): the tail's fragments lie
//   behind the k nearest, so the light, its one shadow tap and its direction are taken at their mean depth,
//   and their sines from the alpha-weighted mean of T T^T: per fragment the tail only adds up its inputs;
// - Eq. 1 is read as visibility: V = sum_i w_i (1 - alpha)^(k d_i), d_i the distance behind the first
//   occluder at tap i in shadow-map depth units, so R = V (R_d + R_R + R_TRT) and the paper's S_n is
//   1 - V. Taps are Gaussian (sigma 1 texel) on a 5x5 grid for the core, the centre tap for the tail;
// - a NaN or infinite input shades to 0, and specular exponents are taken within [0, 1024];
// - the tail accumulates premultiplied colour and alpha (sum c a, sum a) and its transmittance
//   T = prod (1 - a); it is composited behind the core as its alpha-weighted mean colour times (1 - T)
//   over the background times T: exact for one tail fragment, order-independent for many;
// - fragments with alpha below 1/255 are dropped before they reach a list.
#pragma once

#include <glm/gtc/packing.hpp>

#include "detail/shared.hpp"
#include "surface.hpp"

DSTRANS_SHARED(dst_fragment_node,
DST_FN uint dst_pack_tangent(vec3 tangent) { return packSnorm2x16(dst_octahedral_encode(tangent)); }
DST_FN vec3 dst_unpack_tangent(uint bits) { return dst_octahedral_decode(unpackSnorm2x16(bits)); }
// packUnorm4x8 lets an implementation round a .5 tie either way, and a GPU may compute c * 255 + 0.5 with
// one rounding (fma) where the CPU takes two: so each channel is rounded with integer arithmetic instead.
// c * 2^24 is exact, its truncation the same everywhere, and (x 255 + 2^23) >> 24 rounds halves up without
// overflowing 32 bits. NaN packs as 0, as clamp leaves it undefined.
DST_FN uint dst_unorm8(float c) {
  float v = isnan(c) ? 0.0f : (c < 0.0f ? 0.0f : (c > 1.0f ? 1.0f : c));
  return (uint(v * 16777216.0f) * 255u + 8388608u) >> 24u;
}
DST_FN uint dst_pack_colour(vec4 colour_alpha) {
  return dst_unorm8(colour_alpha.x) | (dst_unorm8(colour_alpha.y) << 8u) | (dst_unorm8(colour_alpha.z) << 16u) |
         (dst_unorm8(colour_alpha.w) << 24u);
}
DST_FN vec4 dst_unpack_colour(uint bits) { return unpackUnorm4x8(bits); }
)

DSTRANS_SHARED(dst_hair,
DST_FN bool dst_finite3(vec3 v) { return !(isnan(v.x) || isnan(v.y) || isnan(v.z) || isinf(v.x) || isinf(v.y) || isinf(v.z)); }
DST_FN float dst_sine(float cosine) {
  float q = 1.0f - cosine * cosine;
  return q > 0.0f ? sqrt(q) : 0.0f;
}
DST_FN float dst_strand_specular(vec3 t, vec3 h, float exponent) {
  if (!dst_finite3(t) || !dst_finite3(h) || isnan(exponent)) return 0.0f;
  float th = dot(t, h);
  float s = dst_sine(th);
  if (!(s > 0.0f) || isinf(th)) return 0.0f;
  float towards = th > -1.0f ? (th >= 0.0f ? 1.0f : (th + 1.0f) * (th + 1.0f) * (1.0f - 2.0f * th)) : 0.0f;
  return towards * pow(s, exponent < 0.0f ? 0.0f : (exponent > 1024.0f ? 1024.0f : exponent));
}
DST_FN vec3 dst_hair_cheap(vec3 t, vec3 l, vec3 colour, vec3 light, float visibility) {
  if (!dst_finite3(t) || !dst_finite3(l) || !dst_finite3(colour) || !dst_finite3(light) || isnan(visibility) ||
      isinf(visibility))
    return vec3(0.0f);
  return colour * light * (dst_sine(dot(t, l)) * visibility);
}
DST_FN vec3 dst_hair_full(vec3 t, vec3 l, vec3 v, vec3 colour, vec3 light, float visibility) {
  if (!dst_finite3(v)) return vec3(0.0f);
  vec3 facing = v - t * dot(t, v);
  float fl = length(facing);
  vec3 n = fl > 0.0f ? facing / fl : vec3(0.0f);
  vec3 hv = l + v;
  float hl = length(hv);
  vec3 h = hl > 0.0f ? hv / hl : n;
  vec3 t1 = normalize(t - n * 0.1f);
  vec3 t2 = normalize(t + n * 0.1f);
  vec3 specular = light * (0.3f * dst_strand_specular(t1, h, 80.0f)) + colour * light * (0.4f * dst_strand_specular(t2, h, 20.0f));
  return dst_hair_cheap(t, l, colour, light, visibility) + specular * visibility;
}
// The tail's cheap shader for all its fragments at once: colour (their sum of colour times alpha) lit by
// `light` and `visibility` with sqrt(1 - l^T M l) for their mean sin(T, L), M being their alpha-weighted
// mean of T T^T (its diagonal in `diag`, its xy, xz and yz in `off`). One fragment's M gives dst_hair_cheap
// exactly; for several, the root of their mean sin^2 is at least their mean sine (Jensen), and equal when
// their sines are.
DST_FN vec3 dst_hair_cheap_mean(vec3 diag, vec3 off, vec3 l, vec3 colour, vec3 light, float visibility) {
  if (!dst_finite3(diag) || !dst_finite3(off) || !dst_finite3(l) || !dst_finite3(colour) || !dst_finite3(light) ||
      isnan(visibility) || isinf(visibility))
    return vec3(0.0f);
  float q = 1.0f - (l.x * l.x * diag.x + l.y * l.y * diag.y + l.z * l.z * diag.z +
                    2.0f * (l.x * l.y * off.x + l.x * l.z * off.y + l.y * l.z * off.z));
  return colour * light * ((q > 0.0f ? (q < 1.0f ? sqrt(q) : 1.0f) : 0.0f) * visibility);
}
DST_FN float dst_shadow_tap_weight(float dx, float dy) { return exp(-0.5f * (dx * dx + dy * dy)); }
DST_FN float dst_hair_transmittance(float alpha, float density, float behind) {
  float e = density * behind;
  if (isnan(e) || e <= 0.0f || isnan(alpha) || alpha <= 0.0f) return 1.0f;
  if (alpha >= 1.0f) return 0.0f;
  return pow(1.0f - alpha, e);
}
)

DSTRANS_SHARED(dst_layers,
DST_FN vec4 dst_tail_add(vec4 tail, vec4 colour_alpha) {
  return vec4(tail.x + colour_alpha.x * colour_alpha.w, tail.y + colour_alpha.y * colour_alpha.w,
              tail.z + colour_alpha.z * colour_alpha.w, tail.w + colour_alpha.w);
}
DST_FN vec3 dst_tail_over(vec3 background, vec4 tail, float transmittance) {
  if (isnan(tail.w) || tail.w <= 0.0f) return background * transmittance;
  return background * transmittance + vec3(tail.x, tail.y, tail.z) * ((1.0f - transmittance) / tail.w);
}
DST_FN vec3 dst_over(vec3 behind, vec4 front) {
  return vec3(front.x, front.y, front.z) * front.w + behind * (1.0f - front.w);
}
DST_FN float dst_wboit_weight(float alpha, float depth) {
  float d = 1.0f - depth;
  float w = alpha * 3000.0f * d * d * d;
  if (isnan(w) || w < 0.01f) return 0.01f;
  return w > 3000.0f ? 3000.0f : w;
}
DST_FN vec3 dst_wboit_resolve(vec3 background, vec4 accum, float revealage) {
  if (isnan(accum.w) || accum.w <= 0.0f) return background;
  return vec3(accum.x, accum.y, accum.z) * ((1.0f - revealage) / accum.w) + background * revealage;
}
)

// Coloured shadows from transparent occluders (TECHNIQUES.md S0, 3.2.1, Eq. 3.1 and 3.2).
//
// A shadow map rendered with an interlace predicate holds, for a transparent occluder, its depth and
// colour on keep-pixels and the opaque occluder behind it on their partners. A lookup samples the texel
// and its partner; the one with the lower alpha is the transparent candidate (d_minA, C_minA), the
// other the opaque one (d_maxA). For a point at light-space depth d_P and a bias b (d = d_P - b):
//   I = 0                                  if d_maxA < d
//   I = min(I_L, C_minA) (1 - alpha_minA)  if d_minA < d <= d_maxA     (min per channel, Eq. 3.2)
//   I = I_L                                otherwise
//
//   glm::vec3 lit = dstrans::shader::dst_transparent_shadow(light, d_p, bias, depth_a, occluder_a, depth_b, occluder_b);
//
// Choices: equal alphas make the texel itself the transparent candidate; the bias moves the point
// towards the light (a positive bias removes self-shadowing acne); dst_opaque_shadow is the plain
// shadow map the thesis compares with, looked up at the texel only.
#pragma once

#include "detail/shared.hpp"

DSTRANS_SHARED(dst_transparent_shadow,
DST_FN vec3 dst_transparent_shadow(vec3 light, float d_p, float bias, float depth_a, vec4 occluder_a, float depth_b,
                                   vec4 occluder_b) {
  bool a_transparent = occluder_a.w <= occluder_b.w;
  float d_min = a_transparent ? depth_a : depth_b;
  float d_max = a_transparent ? depth_b : depth_a;
  vec4 c_min = a_transparent ? occluder_a : occluder_b;
  float d = d_p - bias;
  if (d_max < d) return vec3(0.0f);
  if (d_min < d) return min(light, vec3(c_min.x, c_min.y, c_min.z)) * (1.0f - c_min.w);
  return light;
}
DST_FN vec3 dst_opaque_shadow(vec3 light, float d_p, float bias, float depth) {
  return depth < d_p - bias ? vec3(0.0f) : light;
}
)

// Lighting in the light-accumulation pass (the thesis, Eq. 2.1): Phong without the surface's k_d
// and k_s, which the compose pass applies, plus distance attenuation and spot falloff.
//
//   dstrans::light_sample s = dstrans::shader::dst_phong(n, l, v, 32.0f, light_rgb);
//   float a = dstrans::shader::dst_attenuation(distance, range) * dstrans::shader::dst_spot_falloff(c, co, ci);
//   glm::vec4 r = dstrans::shader::dst_light_reach(1, light_pos, dir, range, co, ci, p);   // to the light, amount
//
// Choices the thesis leaves open, documented here and tested:
// - the specular term has the light's colour, (R.V)^n times the light's RGB; the thesis's light buffer keeps
//   only its mean (field::specular), which an RGB-specular light buffer does not (field::specular_rgb);
// - no light reaches a surface facing away (N.L <= 0), specular included;
// - (R.V)^n is 0 where R.V <= 0, for every n (GLSL leaves pow(0, n) undefined); n = 0 gives 1 elsewhere;
// - attenuation is (1 - d/range)^2 clamped to [0, 1]: 1 at the light, 0 at and past its range, so the
//   light volume's mesh bounds every lit pixel; range <= 0 lights nothing;
// - spot falloff rises smoothly (smoothstep) from the outer cone's cosine to the inner's; equal cones
//   give a hard edge, lit where cos >= cos_outer;
// - a NaN distance, range or angle lights nothing (tested with isnan first: GPUs and GLM disagree on
//   clamp and smoothstep of NaN, and Mesa's GL compiler folds `!(x > 0.0f)` into selects that keep it);
// - a point or spot light exactly at the lit point has no direction to light it from: the direction is 0,
//   so N.L = 0 and the point gets no light (finite, not NaN);
// - a spot cone of 0 degrees lights only its axis; one of 90 degrees lights the half space in front of it.
#pragma once

#include "detail/shared.hpp"
#include "surface.hpp"

DSTRANS_SHARED(dst_phong,
DST_FN dst_light_sample dst_phong(vec3 n, vec3 l, vec3 v, float spec_power, vec3 light) {
  dst_light_sample s = dst_light_sample_zero();
  float ndotl = dot(n, l);
  if (isnan(ndotl) || ndotl <= 0.0f) return s;
  vec3 r = n * (2.0f * ndotl) - l;
  float rdotv = dot(r, v);
  s.light = light * ndotl;
  s.specular = rdotv > 0.0f ? light * pow(rdotv, spec_power) : vec3(0.0f);
  return s;
}
)

DSTRANS_SHARED(dst_attenuation,
DST_FN float dst_attenuation(float distance, float range) {
  if (isnan(range) || range <= 0.0f) return 0.0f;
  float x = 1.0f - distance / range;
  if (isnan(x) || x <= 0.0f) return 0.0f;
  return x >= 1.0f ? 1.0f : x * x;
}
DST_FN float dst_spot_falloff(float cos_angle, float cos_outer, float cos_inner) {
  if (isnan(cos_angle) || isnan(cos_outer) || isnan(cos_inner)) return 0.0f;
  if (cos_inner <= cos_outer) return cos_angle >= cos_outer ? 1.0f : 0.0f;
  float t = (cos_angle - cos_outer) / (cos_inner - cos_outer);
  if (isnan(t) || t <= 0.0f) return 0.0f;
  return t >= 1.0f ? 1.0f : t * t * (3.0f - 2.0f * t);
}
)

// Where a light reaches point p from and how much of it arrives: xyz the unit direction from p towards
// the light, w attenuation times spot falloff. kind: 0 directional (shining along unit `direction`), 1
// point, 2 spot.
DSTRANS_SHARED(dst_light_reach,
DST_FN vec4 dst_light_reach(int kind, vec3 position, vec3 direction, float range, float cos_outer, float cos_inner,
                            vec3 p) {
  if (kind == 0) return vec4(-direction.x, -direction.y, -direction.z, 1.0f);
  vec3 d = position - p;
  float distance = length(d);
  vec3 to_light = !isnan(distance) && distance > 0.0f ? d / distance : vec3(0.0f);
  float amount = dst_attenuation(distance, range);
  if (kind == 2) amount *= dst_spot_falloff(-dot(to_light, direction), cos_outer, cos_inner);
  return vec4(to_light.x, to_light.y, to_light.z, amount);
}
)

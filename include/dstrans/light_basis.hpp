// Light stored as its projection on a set of axes: a light volume's cell keeps, per
// axis, how much light arrives from around that axis, and a surface of normal N reads back
// sum_i max(0, N . a_i) value_i.
//
//   float w = dstrans::shader::dst_basis_weight(to_light, dstrans::shader::dst_six_axis(i),
//                                               dstrans::shader::dst_six_axis_norm(to_light));
//   value[i] += light_rgb * w;                                   // baking, per light and axis
//   lit += dstrans::shader::dst_facing(n, axis_i) * value[i];    // reading, per axis
//   dstrans::basis user{{...axes...}};                           // any set of unit axes, on the CPU
//
// The normalisation S2 left open. Project each light with weights max(0, L . a_i) / S(L), where
// S(L) = sum_j max(0, L . a_j). Over all normals N (uniform on the sphere) the average of max(0, N . a)
// is 1/4 for a unit axis a, so a surface lit through the basis receives on average
//   sum_i (1/4) max(0, L . a_i) / S(L) = 1/4,
// which is exactly the average of Lambert's max(0, N . L): for every light direction, not only on
// average over lights, and for any set of unit axes. Without it the six axes give sum_i max(0, L . a_i)
// / 4 = (|L.x| + |L.y| + |L.z|) / 4, from 1/4 up to sqrt(3)/4 for a diagonal light, and four axes from
// 0.20 to 0.29 (sqrt(2/3)/4 to 2/sqrt(3)/4): brightness that depends on where the light stands, and a set
// of fewer axes darker than a set of more (S2's observation). A light
// along an axis of the six- or four-axis set has S(L) = 1 and is reproduced exactly: max(0, N . L).
// A light that no axis faces (S(L) = 0, possible only for a set that does not span all directions)
// contributes nothing. Projections are linear in the lights: each light is normalised on its own.
#pragma once

#include <vector>

#include "detail/shared.hpp"

DSTRANS_SHARED(dst_light_basis,
DST_FN float dst_facing(vec3 v, vec3 axis) {
  float d = dot(v, axis);
  return d > 0.0f ? d : 0.0f;
}
DST_FN vec3 dst_six_axis(int i) {
  if (i == 0) return vec3(1.0f, 0.0f, 0.0f);
  if (i == 1) return vec3(-1.0f, 0.0f, 0.0f);
  if (i == 2) return vec3(0.0f, 1.0f, 0.0f);
  if (i == 3) return vec3(0.0f, -1.0f, 0.0f);
  if (i == 4) return vec3(0.0f, 0.0f, 1.0f);
  return vec3(0.0f, 0.0f, -1.0f);
}
DST_FN vec3 dst_four_axis(int i) {
  float s = 0.57735026919f;
  if (i == 0) return vec3(s, s, s);
  if (i == 1) return vec3(s, -s, -s);
  if (i == 2) return vec3(-s, s, -s);
  return vec3(-s, -s, s);
}
DST_FN float dst_six_axis_norm(vec3 l) { return abs(l.x) + abs(l.y) + abs(l.z); }
DST_FN float dst_four_axis_norm(vec3 l) {
  return dst_facing(l, dst_four_axis(0)) + dst_facing(l, dst_four_axis(1)) + dst_facing(l, dst_four_axis(2)) +
         dst_facing(l, dst_four_axis(3));
}
DST_FN float dst_basis_weight(vec3 l, vec3 axis, float norm) {
  if (isnan(norm) || isinf(norm) || norm <= 0.0f) return 0.0f;
  return dst_facing(l, axis) / norm;
}
)

namespace dstrans {

// A set of unit axes to store light on (six_axes and four_axes are S2's; any other set works the same).
struct basis {
  std::vector<glm::vec3> axes;

  // S(L): what a light from direction `l` projects before normalisation.
  float norm(glm::vec3 l) const {
    float s = 0.0f;
    for (const glm::vec3& a : axes) s += shader::dst_facing(l, a);
    return s;
  }
  // The normalised weights of a light from unit direction `l` (towards the light), one per axis.
  std::vector<float> project(glm::vec3 l) const {
    std::vector<float> w;
    const float s = norm(l);
    for (const glm::vec3& a : axes) w.push_back(shader::dst_basis_weight(l, a, s));
    return w;
  }
  // The light a surface of unit normal `n` reads from per-axis values `values`.
  glm::vec3 evaluate(glm::vec3 n, const std::vector<glm::vec3>& values) const {
    glm::vec3 sum(0.0f);
    for (std::size_t i = 0; i < axes.size() && i < values.size(); ++i) sum += shader::dst_facing(n, axes[i]) * values[i];
    return sum;
  }
};

inline basis six_axes() {
  basis b;
  for (int i = 0; i < 6; ++i) b.axes.push_back(shader::dst_six_axis(i));
  return b;
}
inline basis four_axes() {
  basis b;
  for (int i = 0; i < 4; ++i) b.axes.push_back(shader::dst_four_axis(i));
  return b;
}

}  // namespace dstrans

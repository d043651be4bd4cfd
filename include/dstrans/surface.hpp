// The records a layout stores (a G-buffer surface, a light-buffer sample) and the encodings that
// squeeze their fields into UNORM channels. All of it is shared code: C++ and GLSL use this one text.
//
//   dstrans::surface s = dstrans::shader::dst_surface_zero();
//   s.normal = glm::vec3(0.0f, 1.0f, 0.0f);
//   glm::vec3 stored = dstrans::shader::dst_encode_normal(s.normal);   // (0.5, 1, 0.5)
#pragma once

#include "detail/shared.hpp"

// What the G-buffer holds for one pixel (and a shadow map for one occluder: depth, diffuse, alpha).
// diffuse and alpha in [0, 1]; alpha below 1 marks a transparent surface; normal is a world-space unit
// vector; spec_intensity in [0, 1]; spec_power in [0, 255] (the Phong exponent); depth is the
// window-space depth in [0, 1], 1 where nothing was drawn.
DSTRANS_SHARED(dst_surface,
struct dst_surface {
  vec3 diffuse;
  float alpha;
  vec3 normal;
  float spec_intensity;
  float spec_power;
  float depth;
};
DST_FN dst_surface dst_surface_zero() {
  dst_surface s;
  s.diffuse = vec3(0.0f);
  s.alpha = 0.0f;
  s.normal = vec3(0.0f);
  s.spec_intensity = 0.0f;
  s.spec_power = 0.0f;
  s.depth = 0.0f;
  return s;
}
)

// What the light accumulation buffer holds for one pixel: the light that reached it (RGB, without the
// surface's diffuse colour) and the specular response (RGB, without the surface's spec_intensity). The
// thesis's light buffer keeps one number of the specular (field::specular, white); field::specular_rgb keeps
// all three.
DSTRANS_SHARED(dst_light_sample,
struct dst_light_sample {
  vec3 light;
  vec3 specular;
};
DST_FN dst_light_sample dst_light_sample_zero() {
  dst_light_sample s;
  s.light = vec3(0.0f);
  s.specular = vec3(0.0f);
  return s;
}
)

// A unit vector in two numbers of [-1, 1], octahedrally (Cigolle et al. 2014): the k-buffer's tangents and
// the compact G-buffer's normals. A zero or non-finite vector encodes as (0, 0), which decodes to +Z.
DSTRANS_SHARED(dst_octahedral,
DST_FN vec2 dst_octahedral_encode(vec3 n) {
  float s = abs(n.x) + abs(n.y) + abs(n.z);
  if (isnan(s) || isinf(s) || s <= 0.0f) return vec2(0.0f);
  vec2 p = vec2(n.x, n.y) * (1.0f / s);
  if (n.z >= 0.0f) return p;
  return vec2((1.0f - abs(p.y)) * (p.x >= 0.0f ? 1.0f : -1.0f), (1.0f - abs(p.x)) * (p.y >= 0.0f ? 1.0f : -1.0f));
}
DST_FN vec3 dst_octahedral_decode(vec2 e) {
  vec3 n = vec3(e.x, e.y, 1.0f - abs(e.x) - abs(e.y));
  if (n.z < 0.0f) {
    float x = (1.0f - abs(e.y)) * (e.x >= 0.0f ? 1.0f : -1.0f);
    float y = (1.0f - abs(e.x)) * (e.y >= 0.0f ? 1.0f : -1.0f);
    n.x = x;
    n.y = y;
  }
  float len = length(n);
  return len > 0.0f ? n / len : vec3(0.0f, 0.0f, 1.0f);
}
)

// A unit normal in a UNORM target: [-1, 1] maps to [0, 1]; in two UNORM channels, octahedrally.
DSTRANS_SHARED(dst_normal_unorm,
DST_FN vec3 dst_encode_normal(vec3 n) { return n * 0.5f + 0.5f; }
DST_FN vec3 dst_decode_normal(vec3 e) { return e * 2.0f - 1.0f; }
)
DSTRANS_SHARED(dst_normal_octahedral_unorm,
DST_FN vec2 dst_encode_normal_octahedral(vec3 n) { return dst_octahedral_encode(n) * 0.5f + 0.5f; }
DST_FN vec3 dst_decode_normal_octahedral(vec2 e) { return dst_octahedral_decode(e * 2.0f - 1.0f); }
)

// Alpha in a UNORM target: below 1 is transparent, 1 opaque (surface.alpha), and the target must keep the
// difference. Rounding would store any alpha within half a code of 1 (in [0.99804, 1) for 8 bits) as 1,
// so a transparent alpha is stored at most 254/255, which every UNORM of 8 bits or more keeps below its
// largest code; 1 and above store 1. NaN is opaque, as a NaN material alpha is nowhere below 1.
// Decoding is the identity: what comes back below 1 is transparent.
DSTRANS_SHARED(dst_alpha_unorm,
DST_FN bool dst_transparent(float alpha) { return !isnan(alpha) && alpha < 1.0f; }
DST_FN float dst_encode_alpha(float alpha) {
  if (isnan(alpha) || !dst_transparent(alpha)) return 1.0f;
  return alpha > 254.0f / 255.0f ? 254.0f / 255.0f : alpha;
}
DST_FN float dst_decode_alpha(float e) { return e; }
)

// The thesis's white specular (Table 3.2): one number for the three, their mean, read back as grey. A white
// light's highlight keeps its value; a coloured light's comes out white at the light's mean intensity.
DSTRANS_SHARED(dst_white_specular,
DST_FN float dst_encode_white_specular(vec3 s) { return (s.x + s.y + s.z) * (1.0f / 3.0f); }
DST_FN vec3 dst_decode_white_specular(float e) { return vec3(e); }
)

// A Phong exponent in a UNORM target: [0, 255] maps to [0, 1], so 8 bits keep every integer power.
DSTRANS_SHARED(dst_spec_power_unorm,
DST_FN float dst_encode_spec_power(float p) { return p * (1.0f / 255.0f); }
DST_FN float dst_decode_spec_power(float e) { return e * 255.0f; }
)

namespace dstrans {
using surface = shader::dst_surface;
using light_sample = shader::dst_light_sample;
}  // namespace dstrans

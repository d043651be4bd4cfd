// Interlace predicates: which pixels of a single-layer G-buffer (or shadow map) may keep a transparent
// fragment, and where each pixel finds the other layer (its partner).
//
//   using I = dstrans::interlace::rows;                       // the thesis's (Pangerl's) predicate
//   bool keep = I::keep({x, y}, {w, h});                       // false: discard the transparent fragment
//   glm::ivec2 other = I::partner({x, y}, {w, h});
//   dstrans::glsl::source src;
//   dstrans::glsl::add_interlace<I>(src);                      // dst_interlace_keep / _partner in GLSL
//
// Pixels are (column from the left, row from the top) of the image as stored, on GL and Vulkan alike;
// `size` is the image's width and height. Behaviour at the edges, for pixels inside the image:
// - rows: odd rows keep transparency (row 0 is even, so a 1-row image shows no glass). The partner is
//   the row above, as the thesis's compose pass samples it; row 0 takes row 1. Every pixel and its
//   partner then differ in parity, so one is transparent-capable and one is not, at any height >= 2.
// - columns: the same with columns: odd columns keep, the partner is the column to the left.
// - checker: the 2x2 checkerboard: pixels with x + y odd keep (computed as x xor y, which cannot overflow); the partner is the left neighbour
//   (column 1 for column 0), or, in a 1-pixel-wide image, the row neighbour as for rows.
// - none: every pixel keeps transparency and is its own partner (no interlacing: one layer only).
// Where no partner exists (a 1-pixel extent along the predicate's axis), the partner is the pixel itself.
#pragma once

#include <string>

#include "detail/shared.hpp"
#include "glsl.hpp"
#include "surface.hpp"

// A pixel's row counted from the other edge of the image: from the top to from the bottom and back. A pixel
// outside the image has no row to turn over and stays where it is.
DSTRANS_SHARED(dst_flip_rows,
DST_FN ivec2 dst_flip_rows(ivec2 p, ivec2 size) {
  if (p.y < 0 || p.y >= size.y) return p;
  return ivec2(p.x, size.y - 1 - p.y);
}
)

DSTRANS_SHARED(dst_interlace_rows,
DST_FN bool dst_rows_keep(ivec2 p, ivec2 size) { return (p.y & 1) == 1; }
DST_FN ivec2 dst_rows_partner(ivec2 p, ivec2 size) {
  if (size.y < 2) return p;
  return ivec2(p.x, p.y > 0 ? p.y - 1 : 1);
}
)

DSTRANS_SHARED(dst_interlace_columns,
DST_FN bool dst_columns_keep(ivec2 p, ivec2 size) { return (p.x & 1) == 1; }
DST_FN ivec2 dst_columns_partner(ivec2 p, ivec2 size) {
  if (size.x < 2) return p;
  return ivec2(p.x > 0 ? p.x - 1 : 1, p.y);
}
)

DSTRANS_SHARED(dst_interlace_checker,
DST_FN bool dst_checker_keep(ivec2 p, ivec2 size) { return ((p.x ^ p.y) & 1) == 1; }
DST_FN ivec2 dst_checker_partner(ivec2 p, ivec2 size) {
  if (size.x >= 2) return ivec2(p.x > 0 ? p.x - 1 : 1, p.y);
  if (size.y >= 2) return ivec2(p.x, p.y > 0 ? p.y - 1 : 1);
  return p;
}
)

DSTRANS_SHARED(dst_interlace_none,
DST_FN bool dst_none_keep(ivec2 p, ivec2 size) { return true; }
DST_FN ivec2 dst_none_partner(ivec2 p, ivec2 size) { return p; }
)

// Edge-aware reconstruction of the other layer: instead of the partner's sample alone, the
// samples of the other layer around a pixel (its 4-neighbours that the predicate puts in the other layer:
// above and below for rows, left and right for columns, all four for the checker) are averaged with the
// partner, each weighted by how surely it shows the same surface as the partner, in the spirit of
// inferred lighting's discontinuity-sensitive filter. dst_layer_similarity is 0 across a change of layer
// (transparent against opaque), a depth step of 5% of the view distance or a turn of the normal by 37
// degrees, and 1 for the same surface; window depths d give the relative distance step as
// |d_a - d_b| / (1 - max(d_a, d_b)) for a perspective depth (0 near, 1 far, far plane >> near plane).
// dst_reconstruct adds each neighbour's difference from the partner in proportion, so a layer that is
// the same everywhere comes back exactly, and a neighbour across an edge (weight 0) adds nothing.
DSTRANS_SHARED(dst_reconstruct,
DST_FN float dst_layer_similarity(float depth_a, vec3 normal_a, float alpha_a, float depth_b, vec3 normal_b, float alpha_b) {
  if (dst_transparent(alpha_a) != dst_transparent(alpha_b)) return 0.0f;
  float nearest_far = 1.0f - max(depth_a, depth_b);
  float gap = abs(depth_a - depth_b) / max(nearest_far, 1e-7f);
  if (isnan(gap)) return 0.0f;
  float by_depth = 1.0f - gap * 20.0f;
  float by_normal = 1.0f - (1.0f - dot(normal_a, normal_b)) * 5.0f;
  if (isnan(by_normal)) return 0.0f;  // before the select below, which a GPU compiler may turn into min()
  float s = by_depth < by_normal ? by_depth : by_normal;
  if (isnan(s) || s <= 0.0f) return 0.0f;
  return s < 1.0f ? s : 1.0f;
}
DST_FN vec4 dst_reconstruct(vec4 partner, vec4 a, vec4 b, vec4 c, vec3 weights) {
  vec3 w = weights;
  if (any(isnan(w))) w = vec3(0.0f);
  w = max(w, vec3(0.0f));
  return partner + (w.x * (a - partner) + w.y * (b - partner) + w.z * (c - partner)) / (1.0f + w.x + w.y + w.z);
}
)

// Temporal interlacing's history sample lies off the pixel's ray, and taking it alone copies a gradient
// (a curved pane's shading) a fraction of a pixel off. So it is interpolated linearly with one sample on
// each axis, in proportion to how surely that sample shows the same surface (dst_layer_similarity):
// - across the interlace, with the previous frame's neighbour on the side the reprojected point lies:
//   offset.x is the point's distance from the history sample's centre (in pixels), and is the share;
// - along it, with this frame's sample of the same layer on the pixel's other side, one pixel from the
//   pixel: offset.y is the history sample's distance from the pixel now, and the share a / (1 + a)
//   weighs two samples a and 1 away (none at 0; half at 1).
// Offsets beyond a pixel count as one; a NaN offset or similarity shares nothing.
// Under a moving camera the history also holds what this frame cannot see at all: a sliver one pixel thin
// that the new sample grid steps over. dst_history_box keeps each component of the history's colour `v`
// within the range of this frame's samples `a` and `b` of the same layer on either side of the pixel,
// widened on each side by that range and 0.05, so a gradient survives and a sliver does not; a NaN bound
// holds nothing, and a NaN component comes back as the bounds' midpoint.
DSTRANS_SHARED(dst_history_blend,
DST_FN vec2 dst_history_shares(vec2 offset, vec2 similarity) {
  vec2 a = abs(offset);
  vec2 s = similarity;
  if (isnan(a.x) || isnan(s.x)) s.x = 0.0f;
  if (isnan(a.y) || isnan(s.y)) s.y = 0.0f;
  if (isnan(a.x)) a.x = 0.0f;
  if (isnan(a.y)) a.y = 0.0f;
  a = min(a, vec2(1.0f));
  s = clamp(s, vec2(0.0f), vec2(1.0f));
  return vec2(a.x, a.y / (1.0f + a.y)) * s;
}
DST_FN vec3 dst_history_box(vec3 v, vec3 a, vec3 b) {
  vec3 r = v;
  for (int i = 0; i < 3; ++i) {
    if (isnan(a[i]) || isnan(b[i])) continue;
    float lo = min(a[i], b[i]), hi = max(a[i], b[i]), margin = hi - lo + 0.05f;
    r[i] = isnan(v[i]) ? 0.5f * (lo + hi) : clamp(v[i], lo - margin, hi + margin);
  }
  return r;
}
DST_FN dst_surface dst_surface_mix(dst_surface a, dst_surface b, float t) {
  dst_surface r = a;
  r.diffuse = a.diffuse + (b.diffuse - a.diffuse) * t;
  r.alpha = a.alpha + (b.alpha - a.alpha) * t;
  vec3 n = a.normal + (b.normal - a.normal) * t;
  if (dot(n, n) > 0.0f) r.normal = normalize(n);
  r.spec_intensity = a.spec_intensity + (b.spec_intensity - a.spec_intensity) * t;
  r.spec_power = a.spec_power + (b.spec_power - a.spec_power) * t;
  r.depth = a.depth + (b.depth - a.depth) * t;
  return r;
}
DST_FN dst_light_sample dst_light_mix(dst_light_sample a, dst_light_sample b, float t) {
  dst_light_sample r;
  r.light = a.light + (b.light - a.light) * t;
  r.specular = a.specular + (b.specular - a.specular) * t;
  return r;
}
)

namespace dstrans {
namespace interlace {

#define DSTRANS_INTERLACE(kind)                                                                      \
  struct kind {                                                                                      \
    static constexpr const char* name = #kind;                                                       \
    static constexpr const shared_text& text = ::dstrans::text::dst_interlace_##kind;                \
    static bool keep(glm::ivec2 p, glm::ivec2 size) { return shader::dst_##kind##_keep(p, size); }    \
    static glm::ivec2 partner(glm::ivec2 p, glm::ivec2 size) { return shader::dst_##kind##_partner(p, size); } \
  };
DSTRANS_INTERLACE(rows)
DSTRANS_INTERLACE(columns)
DSTRANS_INTERLACE(checker)
DSTRANS_INTERLACE(none)
#undef DSTRANS_INTERLACE

}  // namespace interlace

namespace glsl {

// Appends predicate I and binds the generic names the passes call:
//   bool dst_interlace_keep(ivec2 pixel, ivec2 size); ivec2 dst_interlace_partner(ivec2 pixel, ivec2 size);
// or, with `as`, AS_keep and AS_partner (for a pass that looks shadow maps up under the generic names and
// also pairs the G-buffer's pixels by another predicate). Their pixels count rows as src.pixel_rows() says;
// the predicate sees them from the top.
template <class I>
void add_interlace(source& src, const std::string& as = "dst_interlace") {
  src.add_shared(I::text);
  const std::string k = std::string("dst_") + I::name;
  if (src.pixel_rows() == rows::from_top) {
    src.add("// dstrans interlace predicate \"" + std::string(I::name) + "\"\n" +
                "bool " + as + "_keep(ivec2 pixel, ivec2 size) { return " + k + "_keep(pixel, size); }\n" +
                "ivec2 " + as + "_partner(ivec2 pixel, ivec2 size) { return " + k + "_partner(pixel, size); }\n",
            __FILE__, __LINE__);
    return;
  }
  src.add_shared(text::dst_flip_rows);
  src.add("// dstrans interlace predicate \"" + std::string(I::name) + "\", pixels counted from the bottom row\n" +
              "bool " + as + "_keep(ivec2 pixel, ivec2 size) { return " + k + "_keep(dst_flip_rows(pixel, size), size); }\n" +
              "ivec2 " + as + "_partner(ivec2 pixel, ivec2 size) {\n" +
              "  return dst_flip_rows(" + k + "_partner(dst_flip_rows(pixel, size), size), size);\n}\n",
          __FILE__, __LINE__);
}

}  // namespace glsl
}  // namespace dstrans

// Light volumes: the light of a scene baked into a grid over a transparent object's
// bounds, stored per cell in RGBA8 texels, for particles to read instead of lighting each fragment. A cell
// keeps either the light projected on a basis of axes (light_basis.hpp; S2's six axes: 18 values in five
// texels, 20 bytes) or the light's moments (three texels, 12 bytes; dst_light_moments).
//
//   std::vector<dstrans::volume_grid> grids{dstrans::fit_grid(lo, hi, {16, 24, 16}), ...};
//   const dstrans::volume_model m = dstrans::light_moments();        // or dstrans::on_axes(dstrans::six_axes())
//   dstrans::volume_atlas atlas = dstrans::pack_volumes(grids, m.texels());   // regions along X, texels along Y
//   float range = dstrans::volume_range(grids[0], lights);          // what a value of region 0 can reach
//   dstrans::glsl::source cs;
//   dstrans::glsl::add_light_volume_bake(cs, m);   // one invocation per cell, 4x4x4 groups
//   // clear the atlas (an RGBA8 3D image) to 0; per list of lights: dispatch bake_groups(atlas), lights at
//   // binding 0, the atlas as a storage image at 1, bake_blocks(atlas, ranges) at 2
//   std::vector<glm::vec4> texels = dstrans::bake_light_volume(atlas, m, lights);   // the CPU's, unscaled
//   dstrans::glsl::add_light_volume_fetch(vs, m);  // dst_volume_texels(atlas, slab, p, region..., t): a cell's texels
//   dstrans::glsl::add_light_volume_read(fs, m);   // dst_volume_light(t, n, range): their light for normal n
//
// Choices: a cell is sampled at its centre, origin + (id + 0.5) * scale, with a scale per axis fitted to
// the bounds (the group count is rounded up; invocations past the grid return). A cell's values go in
// order, four to a texel, each texel of a cell in its own slab of the atlas. A region's values are stored
// as fractions of its range, an upper bound from the lights alone (volume_range), so that they fit unorm8
// whatever the scene's units. The bake adds into the atlas in place (load, add, store): each invocation
// owns its texels, so dispatches (all unshadowed lights in one, each shadowed spot light in its own,
// right after its shadow map is drawn) add up without atomics and without a float copy of the atlas, at
// the price of one rounding a dispatch. The lights use dst_light_reach, so attenuation and spot falloff
// are those of the deferred light pass.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "glsl.hpp"
#include "light_basis.hpp"
#include "phong.hpp"

// Where a particle at world position p reads region (origin, scale, dims) of an atlas of atlas_size texels
// whose region starts at texel offset: a 3D texture coordinate, clamped half a cell inside the region so
// that trilinear filtering never blends in a neighbouring region.
DSTRANS_SHARED(dst_volume_texcoord,
DST_FN float dst_volume_axis(float p, float origin, float scale, float offset, float dims, float atlas) {
  if (isnan(atlas) || isinf(atlas) || atlas <= 0.0f) return 0.0f;
  float local = (p - origin) / scale;
  if (isnan(local) || local < 0.5f) local = 0.5f;
  if (local > dims - 0.5f) local = dims - 0.5f;
  return (offset + local) / atlas;
}
DST_FN vec3 dst_volume_texcoord(vec3 p, vec3 origin, vec3 scale, vec3 offset, vec3 dims, vec3 atlas_size) {
  return vec3(dst_volume_axis(p.x, origin.x, scale.x, offset.x, dims.x, atlas_size.x),
              dst_volume_axis(p.y, origin.y, scale.y, offset.y, dims.y, atlas_size.y),
              dst_volume_axis(p.z, origin.z, scale.z, offset.z, dims.z, atlas_size.z));
}
)

// The light's moments (L1): per colour channel, the light's total M0 and its sum along the directions it
// comes from M1 (|M1| <= M0), stored as the texel (M0 + M1) / 2, M0: four values a channel, none negative,
// linear in the lights (so they add and filter). A surface of normal n reads them back with Geomerics'
// non-linear reconstruction ("Reconstructing diffuse lighting from spherical harmonic data", CEDEC 2015):
// a lobe around M1 of sharpness p = 1 + 2r, r = |M1| / M0, over a constant part, whose average over all
// normals is M0 / 4 (Lambert's, as the axes' normalisation also keeps) and which gives one light its full
// strength where n faces it and nothing where n faces away. Measured on smoke.json (8 cells a side, RGBA8):
// RMSE 3.3 against the per-fragment reference, where S2's six axes give 5.7 and fourteen axes 4.9; the axes'
// error is the direction the light comes from (8 to 32 cells change it by 0.1-0.3), which the lobe follows.
// A light with no direction (a point light at the cell's centre) adds nothing, as it lights no surface.
DSTRANS_SHARED(dst_light_moments,
DST_FN vec4 dst_moment_weights(vec3 l) {
  if (isnan(l.x) || isnan(l.y) || isnan(l.z) || dot(l, l) <= 0.0f) return vec4(0.0f);
  return vec4(0.5f + 0.5f * l.x, 0.5f + 0.5f * l.y, 0.5f + 0.5f * l.z, 1.0f);
}
DST_FN float dst_moments_light(vec4 t, vec3 n) {
  float m0 = t.w;
  if (isnan(m0) || m0 <= 0.0f) return 0.0f;
  vec3 m1 = vec3(2.0f * t.x - m0, 2.0f * t.y - m0, 2.0f * t.z - m0);
  float len = length(m1);
  float r = len / m0;
  if (isnan(r)) r = 0.0f;
  r = r > 1.0f ? 1.0f : r;
  float c = len > 0.0f ? dot(n, m1) / len : 0.0f;
  if (isnan(c)) c = 0.0f;  // a NaN normal reads as one at right angles to the light
  float q = 0.5f + 0.5f * (c > 1.0f ? 1.0f : c < -1.0f ? -1.0f : c);
  float p = 1.0f + 2.0f * r;
  float a = (1.0f - r) / (1.0f + r);
  return 0.25f * m0 * (a + (1.0f - a) * (p + 1.0f) * pow(q, p));
}
)

namespace dstrans {

// What a light volume keeps per cell: the light projected on a basis's axes (RGB each), or its moments.
struct volume_model {
  enum class kind { axes, moments } what = kind::axes;
  basis axes;  // kind::axes only
  // Values a cell: three an axis, or four for each of R, G and B.
  int values() const { return what == kind::moments ? 12 : 3 * int(axes.axes.size()); }
  // RGBA8 texels a cell (each in its own slab of the atlas), and their bytes.
  int texels() const { return (values() + 3) / 4; }
  int bytes_per_cell() const { return 4 * texels(); }
};
inline volume_model on_axes(basis b) { return {volume_model::kind::axes, std::move(b)}; }
inline volume_model light_moments() { return {volume_model::kind::moments, {}}; }

// A grid: its first cell's corner, the size of a cell per axis, the number of cells per axis.
struct volume_grid {
  glm::vec4 origin{0.0f};
  glm::vec4 scale{1.0f};
  glm::ivec4 dims{1};
};

// A light as the bake reads it (std430): position and kind (0 directional, 1 point, 2 spot), direction and
// range, colour times intensity and the outer cone's cosine, the inner cone's cosine in x (y, z and w are
// the engine's: the shadow hook of add_light_volume_bake may read them).
struct volume_light {
  glm::vec4 position_kind{0.0f};
  glm::vec4 direction_range{0.0f, -1.0f, 0.0f, 10.0f};
  glm::vec4 colour_cos_outer{1.0f, 1.0f, 1.0f, 0.0f};
  glm::vec4 cos_inner{0.0f};
};

// The grid of `dims` cells spanning the box from `lo` to `hi`.
inline volume_grid fit_grid(glm::vec3 lo, glm::vec3 hi, glm::ivec3 dims) {
  volume_grid g;
  g.origin = glm::vec4(lo, 0.0f);
  g.scale = glm::vec4((hi - lo) / glm::vec3(glm::max(dims, glm::ivec3(1))), 0.0f);
  g.dims = glm::ivec4(glm::max(dims, glm::ivec3(1)), 0);
  return g;
}

// An upper bound of every value a bake of `lights` stores in grid `g` (either model): each light's
// brightest channel at its strongest over the grid's box (attenuated to the box's nearest point, spot
// falloff and shadows at most 1). 0 where no light reaches the box; a non-finite light counts as none.
inline float volume_range(const volume_grid& g, const std::vector<volume_light>& lights) {
  const glm::vec3 lo(g.origin), hi = lo + glm::vec3(g.scale) * glm::vec3(glm::ivec3(g.dims));
  float sum = 0.0f;
  for (const volume_light& l : lights) {
    const glm::vec3 c(l.colour_cos_outer), p(l.position_kind);
    if (!std::isfinite(c.x + c.y + c.z)) continue;
    const float brightest = std::max({c.x, c.y, c.z, 0.0f});
    const bool directional = int(l.position_kind.w + 0.5f) == 0;
    const float reach = directional ? 1.0f : shader::dst_attenuation(glm::distance(p, glm::clamp(p, glm::min(lo, hi), glm::max(lo, hi))), l.direction_range.w);
    if (std::isfinite(reach)) sum += brightest * reach;
  }
  return sum;
}

// Several objects' grids in one 3D texture: regions side by side along X (S2), a cell's texels in slabs
// along Y (texel k of a region's cell starts slab * k texels above its texel 0); texels past a shorter
// region's height or depth are unused.
struct volume_atlas {
  std::vector<volume_grid> regions;
  std::vector<glm::ivec3> offsets;  // each region's first texel (texel 0)
  int per_cell = 1, slab = 0;       // texels a cell; slab: the tallest region's height
  glm::ivec3 size{0};
};

inline volume_atlas pack_volumes(const std::vector<volume_grid>& grids, int texels_per_cell = 1) {
  volume_atlas a;
  a.regions = grids;
  a.per_cell = texels_per_cell < 1 ? 1 : texels_per_cell;
  glm::ivec3 used(0);
  for (const volume_grid& g : grids) {
    a.offsets.push_back({used.x, 0, 0});
    used = {used.x + g.dims.x, std::max(used.y, g.dims.y), std::max(used.z, g.dims.z)};
  }
  a.slab = used.y;
  a.size = {used.x, used.y * a.per_cell, used.z};
  return a;
}

// The atlas texel (x fastest) that holds texel `k` of cell `cell` of region `r`.
inline std::size_t atlas_texel(const volume_atlas& a, std::size_t r, glm::ivec3 cell, int k = 0) {
  const glm::ivec3 t = a.offsets[r] + cell + glm::ivec3(0, k * a.slab, 0);
  return (std::size_t(t.z) * std::size_t(a.size.y) + std::size_t(t.y)) * std::size_t(a.size.x) + std::size_t(t.x);
}

// What the bake reads of region `r` (std430, one a region at its regions binding): the region's grid, its
// first texel with the slab height in w, the atlas's size, the region's range and its inverse (0 for a
// range of 0).
struct volume_bake_block {
  volume_grid grid;
  glm::ivec4 offset_slab{0};
  glm::ivec4 atlas_size{0};
  glm::vec4 range{0.0f};
};
inline volume_bake_block bake_block(const volume_atlas& a, std::size_t r, float range) {
  const float inverse = range > 0.0f && std::isfinite(range) ? 1.0f / range : 0.0f;
  return {a.regions[r], glm::ivec4(a.offsets[r], a.slab), glm::ivec4(a.size, 0), glm::vec4(range, inverse, 0.0f, 0.0f)};
}
// Every region's block, region r with ranges[r].
inline std::vector<volume_bake_block> bake_blocks(const volume_atlas& a, const std::vector<float>& ranges) {
  std::vector<volume_bake_block> out;
  for (std::size_t r = 0; r < a.regions.size(); ++r) out.push_back(bake_block(a, r, r < ranges.size() ? ranges[r] : 0.0f));
  return out;
}
// The work groups of one bake dispatch: every texel of the atlas's first slab (all regions at once), four
// a side (add_light_volume_bake's group size); none for an empty atlas.
inline glm::ivec3 bake_groups(const volume_atlas& a) { return (glm::ivec3(a.size.x, a.slab, a.size.z) + 3) / 4; }

// The light at one cell's centre, added into `values` (model m's values(), in order).
inline void add_cell_light(const volume_grid& g, const volume_model& m, const std::vector<volume_light>& lights, glm::ivec3 id,
                           float* values) {
  const glm::vec3 p = glm::vec3(g.origin) + (glm::vec3(id) + 0.5f) * glm::vec3(g.scale);
  for (const volume_light& l : lights) {
    const glm::vec4 reach = shader::dst_light_reach(int(l.position_kind.w + 0.5f), glm::vec3(l.position_kind), glm::vec3(l.direction_range),
                                                    l.direction_range.w, l.colour_cos_outer.w, l.cos_inner.x, p);
    const glm::vec3 to_light(reach), colour = glm::vec3(l.colour_cos_outer) * reach.w;
    if (m.what == volume_model::kind::moments) {
      const glm::vec4 w = shader::dst_moment_weights(to_light);
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 4; ++k) values[4 * c + k] += colour[c] * w[k];
      continue;
    }
    const float norm = m.axes.norm(to_light);
    for (std::size_t a = 0; a < m.axes.axes.size(); ++a)
      for (int c = 0; c < 3; ++c) values[3 * a + std::size_t(c)] += colour[c] * shader::dst_basis_weight(to_light, m.axes.axes[a], norm);
  }
}

// The bake on the CPU (no shadows): every region of `a` lit by `lights`, as the atlas's texels before they
// are scaled by the range (the GPU's texels times its region's range).
inline std::vector<glm::vec4> bake_light_volume(const volume_atlas& a, const volume_model& m, const std::vector<volume_light>& lights) {
  std::vector<glm::vec4> texels(std::size_t(a.size.x) * std::size_t(a.size.y) * std::size_t(a.size.z), glm::vec4(0.0f));
  std::vector<float> values(std::size_t(4 * m.texels()));
  for (std::size_t r = 0; r < a.regions.size(); ++r) {
    const volume_grid& g = a.regions[r];
    for (int z = 0; z < g.dims.z; ++z)
      for (int y = 0; y < g.dims.y; ++y)
        for (int x = 0; x < g.dims.x; ++x) {
          std::fill(values.begin(), values.end(), 0.0f);
          add_cell_light(g, m, lights, {x, y, z}, values.data());
          for (int k = 0; k < m.texels() && k < a.per_cell; ++k)
            texels[atlas_texel(a, r, {x, y, z}, k)] = glm::vec4(values[std::size_t(4 * k)], values[std::size_t(4 * k + 1)],
                                                                 values[std::size_t(4 * k + 2)], values[std::size_t(4 * k + 3)]);
        }
  }
  return texels;
}

// The light a surface of unit normal `n` reads from one cell's texels (m.texels() of them, unscaled).
inline glm::vec3 read_cell_light(const volume_model& m, const glm::vec4* texels, glm::vec3 n) {
  if (m.what == volume_model::kind::moments)
    return {shader::dst_moments_light(texels[0], n), shader::dst_moments_light(texels[1], n), shader::dst_moments_light(texels[2], n)};
  glm::vec3 sum(0.0f);
  auto value = [&](std::size_t i) { return texels[i / 4][int(i % 4)]; };
  for (std::size_t a = 0; a < m.axes.axes.size(); ++a)
    sum += shader::dst_facing(n, m.axes.axes[a]) * glm::vec3(value(3 * a), value(3 * a + 1), value(3 * a + 2));
  return sum;
}

namespace glsl {
namespace detail {
// `dst_axes` and `dst_axis[]`: basis b as GLSL constants.
inline std::string basis_constants(const basis& b) {
  auto number = [](float v) {  // a GLSL float literal: digits with a point or an exponent, then f
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", double(v));
    std::string t(buf);
    if (t.find_first_of(".e") == std::string::npos) t += ".0";
    return t + "f";
  };
  std::string axes = "const int dst_axes = " + std::to_string(b.axes.size()) + ";\nconst vec3 dst_axis[" +
                     std::to_string(b.axes.size()) + "] = vec3[](";
  for (std::size_t i = 0; i < b.axes.size(); ++i)
    axes += (i ? ", " : "") + ("vec3(" + number(b.axes[i].x) + ", " + number(b.axes[i].y) + ", " + number(b.axes[i].z) + ")");
  return axes + ");\n";
}
// Value i of a cell as GLSL, from its texels `t[]`: "t[1].z".
inline std::string value_of(std::size_t i) { return "t[" + std::to_string(i / 4) + "]." + "xyzw"[i % 4]; }
// DST_VOLUME_TEXELS, the texels of a cell of model m, for the fetch and the read (once, whichever comes first).
inline std::string texels_define(const volume_model& m) {
  return "#ifndef DST_VOLUME_TEXELS\n#define DST_VOLUME_TEXELS " + std::to_string(m.texels()) + "\n#endif\n";
}
}  // namespace detail

// The bake as a compute shader for model `m`: lights at storage binding `first_binding`, the atlas (an
// rgba8 image3D, added to) at the next, every region's volume_bake_block (bake_blocks) at the one after;
// one dispatch of bake_groups(atlas) bakes every region, an invocation a texel of the first slab, each
// finding its region by its X (regions lie side by side along X). With `shadow_hook` non-empty, that GLSL
// is placed before main() and must define
//   vec3 dst_volume_shadow(dst_volume_light l, vec3 p, vec3 light)
// which the bake calls on each light's colour at each cell: the light that reaches p past the light's
// shadow map (a shadowed spot light's dispatch; the engine knows its map), at most `light`.
inline void add_light_volume_bake(source& src, const volume_model& m, int first_binding = 0, const std::string& shadow_hook = "") {
  src.add_shared(text::dst_light_reach);
  const bool moments = m.what == volume_model::kind::moments;
  src.add_shared(moments ? text::dst_light_moments : text::dst_light_basis);
  const std::string l = std::to_string(first_binding), c = std::to_string(first_binding + 1),
                    gb = std::to_string(first_binding + 2);
  src.add("layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;\n"
          "struct dst_volume_light { vec4 position_kind; vec4 direction_range; vec4 colour_cos_outer; vec4 cos_inner; };\n"
          "layout(std430, binding = " + l + ") readonly buffer dst_volume_lights { dst_volume_light volume_lights[]; };\n"
          "layout(rgba8, binding = " + c + ") uniform image3D dst_volume_atlas;\n"
          "struct dst_volume_region {\n"
          "  vec4 origin; vec4 scale; ivec4 dims; ivec4 offset_slab; ivec4 atlas_size; vec4 range;\n"
          "};\n"
          "layout(std430, binding = " + gb + ") readonly buffer dst_volume_regions { dst_volume_region regions[]; };\n"
          "const int dst_texels = " + std::to_string(m.texels()) + ";\n" + (moments ? "" : detail::basis_constants(m.axes)),
          __FILE__, __LINE__);
  if (!shadow_hook.empty()) src.add(shadow_hook, "shadow hook", 1);
  const std::string project =
      moments ? "    vec4 w = dst_moment_weights(to_light);\n"
                "    for (int c = 0; c < 3; ++c)\n"
                "      for (int k = 0; k < 4; ++k) values[4 * c + k] += colour[c] * w[k];\n"
              : "    float norm = 0.0f;\n"
                "    for (int a = 0; a < dst_axes; ++a) norm += dst_facing(to_light, dst_axis[a]);\n"
                "    for (int a = 0; a < dst_axes; ++a) {\n"
                "      float w = dst_basis_weight(to_light, dst_axis[a], norm);\n"
                "      for (int c = 0; c < 3; ++c) values[3 * a + c] += colour[c] * w;\n"
                "    }\n";
  src.add(std::string("void main() {\n"
          "  ivec3 texel = ivec3(gl_GlobalInvocationID);\n"
          // A plain loop: Mesa's GL compiled a search written as while (r < n && x >= end of r) so that the
          // bake stored nothing.
          "  int r = 0;  // the last region that starts at or before this X (regions lie in order along X)\n"
          "  for (int i = 1; i < regions.length(); ++i)\n"
          "    if (texel.x >= regions[i].offset_slab.x) r = i;\n"
          "  dst_volume_region region = regions[r];\n"
          "  ivec3 id = texel - region.offset_slab.xyz;\n"
          "  if (any(lessThan(id, ivec3(0))) || any(greaterThanEqual(id, region.dims.xyz))) return;\n"
          "  vec3 p = region.origin.xyz + (vec3(id) + 0.5f) * region.scale.xyz;\n"
          "  float values[4 * dst_texels];\n"
          "  for (int i = 0; i < 4 * dst_texels; ++i) values[i] = 0.0f;\n"
          "  for (int i = 0; i < volume_lights.length(); ++i) {\n"
          "    dst_volume_light l = volume_lights[i];\n"
          "    vec4 reach = dst_light_reach(int(l.position_kind.w + 0.5f), l.position_kind.xyz, l.direction_range.xyz,\n"
          "                                 l.direction_range.w, l.colour_cos_outer.w, l.cos_inner.x, p);\n"
          "    vec3 to_light = reach.xyz, colour = l.colour_cos_outer.xyz * reach.w;\n") +
          (shadow_hook.empty() ? "" : "    if (reach.w > 0.0f) colour = dst_volume_shadow(l, p, colour);\n") + project +
          "  }\n"
          "  for (int k = 0; k < dst_texels; ++k) {\n"
          "    ivec3 t = region.offset_slab.xyz + id + ivec3(0, k * region.offset_slab.w, 0);\n"
          "    vec4 add = vec4(values[4 * k], values[4 * k + 1], values[4 * k + 2], values[4 * k + 3]) * region.range.y;\n"
          "    imageStore(dst_volume_atlas, t, imageLoad(dst_volume_atlas, t) + add);\n"
          "  }\n"
          "}\n",
          __FILE__, __LINE__);
}

// What a particle's shader calls to fetch its cell (model `m`, the atlas a 3D texture laid out by
// pack_volumes with m's texels a cell):
//   void dst_volume_texels(sampler3D atlas, float slab, vec3 p, vec3 origin, vec3 scale, vec3 offset, vec3 dims,
//                          out vec4 t[DST_VOLUME_TEXELS])
// each texel of the cell at world point p of the region (origin, scale, first texel, dims), trilinearly
// filtered (texels are linear in the light, so filtering them filters the light's projection). Fetch per
// pixel as S2 did, or once a particle: the reference pipeline fetches at the particle's centre in the
// vertex shader and passes the texels flat, which takes every texture fetch out of its fragments.
inline void add_light_volume_fetch(source& src, const volume_model& m) {
  src.add_shared(text::dst_volume_texcoord);
  src.add(detail::texels_define(m) +
              "void dst_volume_texels(sampler3D atlas, float slab, vec3 p, vec3 origin, vec3 scale, vec3 offset, vec3 dims,\n"
              "                       out vec4 t[DST_VOLUME_TEXELS]) {\n"
              "  vec3 size = vec3(textureSize(atlas, 0));\n"
              "  vec3 uvw = dst_volume_texcoord(p, origin, scale, offset, dims, size);  // texel 0's\n"
              "  float step = slab / size.y;  // from one texel's slab to the next\n"
              "  for (int k = 0; k < DST_VOLUME_TEXELS; ++k)\n"
              "    t[k] = textureLod(atlas, uvw + vec3(0.0f, float(k) * step, 0.0f), 0.0f);\n"
              "}\n",
          __FILE__, __LINE__);
}

// What a particle's shader calls to turn a cell's texels (dst_volume_texels) into light:
//   vec3 dst_volume_light(vec4 t[DST_VOLUME_TEXELS], vec3 n, float range)
// the light for unit normal n: the sum over axes of max(0, n . axis) times the axis's value, or the
// moments' reconstruction per channel; times the region's range.
inline void add_light_volume_read(source& src, const volume_model& m) {
  const bool moments = m.what == volume_model::kind::moments;
  src.add_shared(moments ? text::dst_light_moments : text::dst_light_basis);
  std::string sum;
  if (moments) {
    sum = "  vec3 sum = vec3(dst_moments_light(t[0], n), dst_moments_light(t[1], n), dst_moments_light(t[2], n));\n";
  } else {
    sum = "  vec3 sum = vec3(0.0f);\n";
    for (std::size_t a = 0; a < m.axes.axes.size(); ++a)
      sum += "  sum += dst_facing(n, dst_axis[" + std::to_string(a) + "]) * vec3(" + detail::value_of(3 * a) + ", " +
             detail::value_of(3 * a + 1) + ", " + detail::value_of(3 * a + 2) + ");\n";
  }
  src.add(detail::texels_define(m) + (moments ? std::string() : detail::basis_constants(m.axes)) +
              "vec3 dst_volume_light(vec4 t[DST_VOLUME_TEXELS], vec3 n, float range) {\n" + sum +
              "  return sum * range;\n"
              "}\n",
          __FILE__, __LINE__);
}

}  // namespace glsl
}  // namespace dstrans

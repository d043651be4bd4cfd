// Light volumes: the light of a scene baked into a grid over a transparent object's
// bounds, stored per cell on a basis of axes (light_basis.hpp), for particles to read instead of lighting
// each fragment.
//
//   std::vector<dstrans::volume_grid> grids{dstrans::fit_grid(lo, hi, {16, 24, 16}), ...};
//   dstrans::volume_atlas atlas = dstrans::pack_volumes(grids, 6);   // regions along X, axes along Y
//   dstrans::glsl::source cs;
//   dstrans::glsl::add_light_volume_bake(cs, dstrans::six_axes());   // one invocation per cell, 4x4x4 groups
//   // per region: dispatch ceil(dims / 4) groups, lights at binding 0, texels at 1, bake_block(atlas, r) at 2;
//   // then copy the texels (vec4 each, x fastest) into a 3D RGBA32F texture of atlas.size
//   std::vector<glm::vec4> texels = dstrans::bake_light_volume(atlas, dstrans::six_axes(), lights);   // the CPU's
//   dstrans::glsl::add_light_volume_read(fs, dstrans::six_axes());   // dst_volume_light(atlas, p, n, region...)
//
// Choices: a cell is sampled at its centre, origin + (id + 0.5) * scale, with a scale per axis fitted to
// the bounds (the group count is rounded up; invocations past the grid return). The accumulation storage
// is a storage buffer laid out as the 3D texture the particles sample (one vec4 per texel, rgb, w unused),
// added to in place: each invocation owns its texels, so dispatches (all unshadowed lights in one, each
// shadowed spot light in its own, right after its shadow map is drawn) add up without atomics, which GL
// and Vulkan lack for floats in their cores; float storage images would work too, but a buffer reads back
// the same way on both APIs and one copy (GL: a pixel-unpack upload, Vulkan: vkCmdCopyBufferToImage) gives
// the filtered texture. The lights use dst_light_reach, so attenuation and spot falloff are those of the
// deferred light pass.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
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

namespace dstrans {

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

// Several objects' grids in one 3D texture: regions side by side along X (S2), the axes of the basis in
// slabs along Y (axis a of a region starts slab * a texels above its axis 0); texels past a shorter
// region's height or depth are unused.
struct volume_atlas {
  std::vector<volume_grid> regions;
  std::vector<glm::ivec3> offsets;  // each region's first texel (axis 0)
  int axes = 1, slab = 0;           // slab: the tallest region's height
  glm::ivec3 size{0};
};

inline volume_atlas pack_volumes(const std::vector<volume_grid>& grids, int axes = 1) {
  volume_atlas a;
  a.regions = grids;
  a.axes = axes < 1 ? 1 : axes;
  glm::ivec3 used(0);
  for (const volume_grid& g : grids) {
    a.offsets.push_back({used.x, 0, 0});
    used = {used.x + g.dims.x, std::max(used.y, g.dims.y), std::max(used.z, g.dims.z)};
  }
  a.slab = used.y;
  a.size = {used.x, used.y * a.axes, used.z};
  return a;
}

// The atlas texel (x fastest) that holds axis `axis` of cell `cell` of region `r`.
inline std::size_t atlas_texel(const volume_atlas& a, std::size_t r, glm::ivec3 cell, int axis = 0) {
  const glm::ivec3 t = a.offsets[r] + cell + glm::ivec3(0, axis * a.slab, 0);
  return (std::size_t(t.z) * std::size_t(a.size.y) + std::size_t(t.y)) * std::size_t(a.size.x) + std::size_t(t.x);
}

// What the bake of region `r` reads at its uniform binding (std140): the region's grid, its first texel
// with the slab height in w, the atlas's size.
struct volume_bake_block {
  volume_grid grid;
  glm::ivec4 offset_slab{0};
  glm::ivec4 atlas_size{0};
};
inline volume_bake_block bake_block(const volume_atlas& a, std::size_t r) {
  return {a.regions[r], glm::ivec4(a.offsets[r], a.slab), glm::ivec4(a.size, 0)};
}

// The light at one cell's centre, added into `values` (one per axis of `b`).
inline void add_cell_light(const volume_grid& g, const basis& b, const std::vector<volume_light>& lights, glm::ivec3 id,
                           glm::vec3* values) {
  const glm::vec3 p = glm::vec3(g.origin) + (glm::vec3(id) + 0.5f) * glm::vec3(g.scale);
  for (const volume_light& l : lights) {
    const glm::vec4 reach = shader::dst_light_reach(int(l.position_kind.w + 0.5f), glm::vec3(l.position_kind), glm::vec3(l.direction_range),
                                                    l.direction_range.w, l.colour_cos_outer.w, l.cos_inner.x, p);
    const glm::vec3 to_light(reach), colour = glm::vec3(l.colour_cos_outer) * reach.w;
    const float norm = b.norm(to_light);
    for (std::size_t a = 0; a < b.axes.size(); ++a) values[a] += colour * shader::dst_basis_weight(to_light, b.axes[a], norm);
  }
}

// The bake on the CPU (no shadows): every region of `a` lit by `lights`, as the texels of the atlas.
inline std::vector<glm::vec4> bake_light_volume(const volume_atlas& a, const basis& b, const std::vector<volume_light>& lights) {
  std::vector<glm::vec4> texels(std::size_t(a.size.x) * std::size_t(a.size.y) * std::size_t(a.size.z), glm::vec4(0.0f));
  std::vector<glm::vec3> values(b.axes.size());
  for (std::size_t r = 0; r < a.regions.size(); ++r) {
    const volume_grid& g = a.regions[r];
    for (int z = 0; z < g.dims.z; ++z)
      for (int y = 0; y < g.dims.y; ++y)
        for (int x = 0; x < g.dims.x; ++x) {
          std::fill(values.begin(), values.end(), glm::vec3(0.0f));
          add_cell_light(g, b, lights, {x, y, z}, values.data());
          for (std::size_t i = 0; i < values.size() && int(i) < a.axes; ++i)
            texels[atlas_texel(a, r, {x, y, z}, int(i))] = glm::vec4(values[i], 0.0f);
        }
  }
  return texels;
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
}  // namespace detail

// The bake as a compute shader for basis `b`: lights at storage binding `first_binding`, the atlas's
// texels (added to) at the next, the region's volume_bake_block at the one after. With `shadow_hook`
// non-empty, that GLSL is placed before main() and must define
//   vec3 dst_volume_shadow(dst_volume_light l, vec3 p, vec3 light)
// which the bake calls on each light's colour at each cell: the light that reaches p past the light's
// shadow map (a shadowed spot light's dispatch; the engine knows its map).
inline void add_light_volume_bake(source& src, const basis& b, int first_binding = 0, const std::string& shadow_hook = "") {
  src.add_shared(text::dst_light_reach);
  src.add_shared(text::dst_light_basis);
  const std::string l = std::to_string(first_binding), c = std::to_string(first_binding + 1),
                    gb = std::to_string(first_binding + 2);
  src.add("layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;\n"
          "struct dst_volume_light { vec4 position_kind; vec4 direction_range; vec4 colour_cos_outer; vec4 cos_inner; };\n"
          "layout(std430, binding = " + l + ") readonly buffer dst_volume_lights { dst_volume_light volume_lights[]; };\n"
          "layout(std430, binding = " + c + ") buffer dst_volume_texels { vec4 volume_texels[]; };\n"
          "layout(std140, binding = " + gb + ") uniform dst_volume_region {\n"
          "  vec4 origin; vec4 scale; ivec4 dims; ivec4 offset_slab; ivec4 atlas_size;\n"
          "} region;\n" + detail::basis_constants(b),
          __FILE__, __LINE__);
  if (!shadow_hook.empty()) src.add(shadow_hook, "shadow hook", 1);
  src.add(std::string("void main() {\n"
          "  ivec3 id = ivec3(gl_GlobalInvocationID);\n"
          "  if (any(greaterThanEqual(id, region.dims.xyz))) return;\n"
          "  vec3 p = region.origin.xyz + (vec3(id) + 0.5f) * region.scale.xyz;\n"
          "  vec3 values[dst_axes];\n"
          "  for (int a = 0; a < dst_axes; ++a) values[a] = vec3(0.0f);\n"
          "  for (int i = 0; i < volume_lights.length(); ++i) {\n"
          "    dst_volume_light l = volume_lights[i];\n"
          "    vec4 reach = dst_light_reach(int(l.position_kind.w + 0.5f), l.position_kind.xyz, l.direction_range.xyz,\n"
          "                                 l.direction_range.w, l.colour_cos_outer.w, l.cos_inner.x, p);\n"
          "    vec3 to_light = reach.xyz, colour = l.colour_cos_outer.xyz * reach.w;\n") +
          (shadow_hook.empty() ? "" : "    if (reach.w > 0.0f) colour = dst_volume_shadow(l, p, colour);\n") +
          "    float norm = 0.0f;\n"
          "    for (int a = 0; a < dst_axes; ++a) norm += dst_facing(to_light, dst_axis[a]);\n"
          "    for (int a = 0; a < dst_axes; ++a) values[a] += colour * dst_basis_weight(to_light, dst_axis[a], norm);\n"
          "  }\n"
          "  for (int a = 0; a < dst_axes; ++a) {\n"
          "    ivec3 t = region.offset_slab.xyz + id + ivec3(0, a * region.offset_slab.w, 0);\n"
          "    volume_texels[(t.z * region.atlas_size.y + t.y) * region.atlas_size.x + t.x].xyz += values[a];\n"
          "  }\n"
          "}\n",
          __FILE__, __LINE__);
}

// What a particle's fragment shader calls to read its light (basis `b`, the atlas a 3D texture laid out by
// pack_volumes with b's axes):
//   vec3 dst_volume_light(sampler3D atlas, float slab, vec3 p, vec3 n, vec3 origin, vec3 scale, vec3 offset, vec3 dims)
// the light at world point p for unit normal n from the region (origin, scale, first texel, dims):
// sum over axes of max(0, n . axis) times the trilinearly filtered value of that axis. Where the axes come
// in opposite pairs (opposite_pairs: S2's six, the fourteen of faces and corners), at most one of a pair
// faces the normal, picked by the sign of n . axis: one fetch a pair and no branches.
inline void add_light_volume_read(source& src, const basis& b) {
  src.add_shared(text::dst_light_basis);
  src.add_shared(text::dst_volume_texcoord);
  const auto pairs = opposite_pairs(b);
  std::string pair_constants;
  if (!pairs.empty()) {
    pair_constants = "const int dst_pairs = " + std::to_string(pairs.size()) + ";\nconst ivec2 dst_pair[" +
                     std::to_string(pairs.size()) + "] = ivec2[](";
    for (std::size_t k = 0; k < pairs.size(); ++k)
      pair_constants += (k ? ", " : "") + ("ivec2(" + std::to_string(pairs[k].first) + ", " + std::to_string(pairs[k].second) + ")");
    pair_constants += ");\n";
  }
  src.add(detail::basis_constants(b) + pair_constants +
              "vec3 dst_volume_light(sampler3D atlas, float slab, vec3 p, vec3 n, vec3 origin, vec3 scale, vec3 offset, vec3 dims) {\n"
              "  vec3 size = vec3(textureSize(atlas, 0));\n"
              "  vec3 uvw = dst_volume_texcoord(p, origin, scale, offset, dims, size);  // axis 0's\n"
              "  float step = slab / size.y;  // from one axis's slab to the next\n"
              "  vec3 sum = vec3(0.0f);\n" +
              (!pairs.empty() ? "  for (int k = 0; k < dst_pairs; ++k) {\n"
                                "    float d = dot(n, dst_axis[dst_pair[k].x]);\n"
                                "    int a = d >= 0.0f ? dst_pair[k].x : dst_pair[k].y;  // the one that faces n\n"
                                "    sum += abs(d) * textureLod(atlas, uvw + vec3(0.0f, float(a) * step, 0.0f), 0.0f).rgb;\n"
                                "  }\n"
                   : "  for (int a = 0; a < dst_axes; ++a) {\n"
                     "    float facing = dst_facing(n, dst_axis[a]);\n"
                     "    if (facing > 0.0f) sum += facing * textureLod(atlas, uvw + vec3(0.0f, float(a) * step, 0.0f), 0.0f).rgb;\n"
                     "  }\n") +
              "  return sum;\n"
              "}\n",
          __FILE__, __LINE__);
}

}  // namespace glsl
}  // namespace dstrans

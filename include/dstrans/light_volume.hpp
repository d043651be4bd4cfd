// Light volumes (TECHNIQUES.md S2): the light of a scene baked into a grid over a transparent object's
// bounds, stored per cell on a basis of axes (light_basis.hpp), for particles to read instead of lighting
// each fragment.
//
//   dstrans::volume_grid g = dstrans::fit_grid(bounds_min, bounds_max, {16, 24, 16});
//   dstrans::glsl::source cs;
//   dstrans::glsl::add_light_volume_bake(cs, dstrans::six_axes());   // one invocation per cell, 4x4x4 groups
//   // dispatch ceil(dims / 4) groups with the lights at binding 0, the cells at 1, the grid at 2
//   std::vector<glm::vec4> cells = dstrans::bake_light_volume(g, dstrans::six_axes(), lights);   // the CPU's
//   dstrans::volume_atlas atlas = dstrans::pack_volumes({g, other});   // regions side by side along X
//   glm::vec3 uvw = dstrans::shader::dst_volume_texcoord(p, origin, scale, offset, dims, atlas_size);
//
// Choices: a cell is sampled at its centre, origin + (id + 0.5) * scale, with a scale per axis fitted to
// the bounds (the group count is rounded up; invocations past the grid return). The accumulation storage
// is a storage buffer of one vec4 per cell and axis (rgb, w unused), added to in place: each invocation
// owns its cell, so dispatches (all unshadowed lights in one, each shadowed spot light in its own) add up
// without atomics, which GL and Vulkan lack for floats in their cores. The lights use dst_light_reach, so
// attenuation and spot falloff are those of the deferred light pass.
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

// A grid: its first cell's corner, the size of a cell per axis, the number of cells per axis (std140).
struct volume_grid {
  glm::vec4 origin{0.0f};
  glm::vec4 scale{1.0f};
  glm::ivec4 dims{1};
  std::size_t cells() const { return std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z); }
};

// A light as the bake reads it (std430): position and kind (0 directional, 1 point, 2 spot), direction and
// range, colour times intensity and the outer cone's cosine, the inner cone's cosine.
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

// The bake on the CPU: the cells (x fastest, then y, then z), each axis's rgb in a vec4.
inline std::vector<glm::vec4> bake_light_volume(const volume_grid& g, const basis& b, const std::vector<volume_light>& lights) {
  std::vector<glm::vec4> cells(g.cells() * b.axes.size(), glm::vec4(0.0f));
  std::vector<glm::vec3> values(b.axes.size());
  for (int z = 0; z < g.dims.z; ++z)
    for (int y = 0; y < g.dims.y; ++y)
      for (int x = 0; x < g.dims.x; ++x) {
        std::fill(values.begin(), values.end(), glm::vec3(0.0f));
        add_cell_light(g, b, lights, {x, y, z}, values.data());
        const std::size_t cell = (std::size_t(z) * std::size_t(g.dims.y) + std::size_t(y)) * std::size_t(g.dims.x) + std::size_t(x);
        for (std::size_t a = 0; a < values.size(); ++a) cells[cell * b.axes.size() + a] = glm::vec4(values[a], 0.0f);
      }
  return cells;
}

// Several objects' grids packed side by side along X in one 3D texture (S2): each region's texel offset
// and the texture's size; texels past a shorter region's height or depth are unused.
struct volume_atlas {
  std::vector<volume_grid> regions;
  std::vector<glm::ivec3> offsets;
  glm::ivec3 size{0};
};

inline volume_atlas pack_volumes(const std::vector<volume_grid>& grids) {
  volume_atlas a;
  a.regions = grids;
  for (const volume_grid& g : grids) {
    a.offsets.push_back({a.size.x, 0, 0});
    a.size = {a.size.x + g.dims.x, std::max(a.size.y, g.dims.y), std::max(a.size.z, g.dims.z)};
  }
  return a;
}

// The atlas texel (x fastest) that holds cell `cell` of region `r`.
inline std::size_t atlas_texel(const volume_atlas& a, std::size_t r, glm::ivec3 cell) {
  const glm::ivec3 t = a.offsets[r] + cell;
  return (std::size_t(t.z) * std::size_t(a.size.y) + std::size_t(t.y)) * std::size_t(a.size.x) + std::size_t(t.x);
}

namespace glsl {

// The bake as a compute shader for basis `b`: lights at storage binding `first_binding`, cells (added to)
// at the next, the grid's uniform block at the one after.
inline void add_light_volume_bake(source& src, const basis& b, int first_binding = 0) {
  src.add_shared(text::dst_light_reach);
  src.add_shared(text::dst_light_basis);
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
  axes += ");\n";
  const std::string l = std::to_string(first_binding), c = std::to_string(first_binding + 1),
                    gb = std::to_string(first_binding + 2);
  src.add("layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;\n"
          "struct dst_volume_light { vec4 position_kind; vec4 direction_range; vec4 colour_cos_outer; vec4 cos_inner; };\n"
          "layout(std430, binding = " + l + ") readonly buffer dst_volume_lights { dst_volume_light volume_lights[]; };\n"
          "layout(std430, binding = " + c + ") buffer dst_volume_cells { vec4 cells[]; };\n"
          "layout(std140, binding = " + gb + ") uniform dst_volume_grid { vec4 origin; vec4 scale; ivec4 dims; } grid;\n" +
              axes +
              "void main() {\n"
              "  ivec3 id = ivec3(gl_GlobalInvocationID);\n"
              "  if (any(greaterThanEqual(id, grid.dims.xyz))) return;\n"
              "  vec3 p = grid.origin.xyz + (vec3(id) + 0.5f) * grid.scale.xyz;\n"
              "  int cell = (id.z * grid.dims.y + id.y) * grid.dims.x + id.x;\n"
              "  vec3 values[dst_axes];\n"
              "  for (int a = 0; a < dst_axes; ++a) values[a] = vec3(0.0f);\n"
              "  for (int i = 0; i < volume_lights.length(); ++i) {\n"
              "    dst_volume_light l = volume_lights[i];\n"
              "    vec4 reach = dst_light_reach(int(l.position_kind.w + 0.5f), l.position_kind.xyz, l.direction_range.xyz,\n"
              "                                 l.direction_range.w, l.colour_cos_outer.w, l.cos_inner.x, p);\n"
              "    vec3 to_light = reach.xyz, colour = l.colour_cos_outer.xyz * reach.w;\n"
              "    float norm = 0.0f;\n"
              "    for (int a = 0; a < dst_axes; ++a) norm += dst_facing(to_light, dst_axis[a]);\n"
              "    for (int a = 0; a < dst_axes; ++a) values[a] += colour * dst_basis_weight(to_light, dst_axis[a], norm);\n"
              "  }\n"
              "  for (int a = 0; a < dst_axes; ++a) cells[cell * dst_axes + a].xyz += values[a];\n"
              "}\n",
          __FILE__, __LINE__);
}

}  // namespace glsl
}  // namespace dstrans

// Whether a triangle mesh encloses space, and which way its triangles face: what lets a pass that keeps
// only the nearest surface (a shadow map) cull a mesh's back faces without changing a texel.
//
//   const int side = dstrans::closed_orientation(shape.positions, shape.indices);
//   // 1: closed, counter-clockwise seen from outside (a box), -1: closed and turned inwards (a room
//   // seen from within), 0: open (a pane), or not one surface that a ray enters before it leaves
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

namespace dstrans {

namespace detail {
// A position's bits as a map key, -0 taken as +0: vertices are the same point when their positions are equal.
inline std::uint64_t position_hash(const glm::vec3& p) {
  std::uint32_t bits[3];
  const glm::vec3 q = p + glm::vec3(0.0f);
  std::memcpy(bits, &q, sizeof bits);
  return (std::uint64_t(bits[0]) * 0x9E3779B97F4A7C15ull) ^ (std::uint64_t(bits[1]) * 0xC2B2AE3D27D4EB4Full) ^ bits[2];
}
struct position_key {
  std::size_t operator()(const glm::vec3& p) const { return std::size_t(position_hash(p)); }
};
inline std::uint32_t find_root(std::vector<std::uint32_t>& parent, std::uint32_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}
}  // namespace detail

// Which side a mesh's triangles (`indices` into `positions`, three a triangle, counter-clockwise facing)
// face when it is closed, by the points themselves: vertices at equal positions are one point, so a seam
// of repeated vertices joins. Closed means that every edge is crossed as often one way as the other by the
// triangles that have it (triangles with two corners at one point, which cover nothing, left out), so that
// the mesh bounds its pieces (the sets of triangles joined by edges) everywhere. 1: every piece encloses a
// positive volume (its triangles face outwards), -1: every piece a negative one (inwards), 0: open, mixed,
// flat (a piece's volume within 1e-6 of its bounding box's), empty, an index out of range or a NaN
// position. For 1, a viewpoint outside a piece (and outside any inside-out fold of it, where the surface
// passes through itself) meets one of its front faces before any of its back faces along every ray.
inline int closed_orientation(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices) {
  std::unordered_map<glm::vec3, std::uint32_t, detail::position_key> point_of;
  std::vector<std::uint32_t> point(positions.size());
  std::vector<glm::vec3> where;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (glm::any(glm::isnan(positions[i]))) return 0;
    const auto [it, added] = point_of.emplace(positions[i], std::uint32_t(where.size()));
    if (added) where.push_back(positions[i]);
    point[i] = it->second;
  }
  std::vector<std::uint32_t> parent(where.size());
  std::iota(parent.begin(), parent.end(), 0u);
  std::unordered_map<std::uint64_t, int> crossings;  // edge a -> b, a < b: +1 each a -> b, -1 each b -> a
  std::vector<std::uint32_t> kept;
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    std::uint32_t c[3];
    for (int k = 0; k < 3; ++k) {
      if (indices[t + std::size_t(k)] >= point.size()) return 0;
      c[k] = point[indices[t + std::size_t(k)]];
    }
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = c[k], b = c[(k + 1) % 3];
      crossings[a < b ? (std::uint64_t(a) << 32) | b : (std::uint64_t(b) << 32) | a] += a < b ? 1 : -1;
      parent[detail::find_root(parent, a)] = detail::find_root(parent, b);
    }
    kept.insert(kept.end(), c, c + 3);
  }
  if (kept.empty()) return 0;
  for (const auto& [edge, n] : crossings)
    if (n != 0) return 0;
  // Each piece's volume and bounds, from its first point: the sum of the tetrahedra its triangles make.
  std::unordered_map<std::uint32_t, double> volume;
  std::unordered_map<std::uint32_t, std::pair<glm::dvec3, glm::dvec3>> box;
  for (std::size_t t = 0; t < kept.size(); t += 3) {
    const std::uint32_t root = detail::find_root(parent, kept[t]);
    const glm::dvec3 o(where[root]), a = glm::dvec3(where[kept[t]]) - o, b = glm::dvec3(where[kept[t + 1]]) - o,
                                     c = glm::dvec3(where[kept[t + 2]]) - o;
    volume[root] += glm::dot(a, glm::cross(b, c)) / 6.0;
    auto [at, added] = box.emplace(root, std::make_pair(glm::dvec3(where[kept[t]]), glm::dvec3(where[kept[t]])));
    for (int k = 0; k < 3; ++k) {
      at->second.first = glm::min(at->second.first, glm::dvec3(where[kept[t + std::size_t(k)]]));
      at->second.second = glm::max(at->second.second, glm::dvec3(where[kept[t + std::size_t(k)]]));
    }
  }
  int side = 0;
  for (const auto& [root, v] : volume) {
    const glm::dvec3 extent = box[root].second - box[root].first;
    if (!(std::abs(v) > 1e-6 * extent.x * extent.y * extent.z) || !std::isfinite(v)) return 0;
    const int s = v > 0.0 ? 1 : -1;
    if (side != 0 && s != side) return 0;
    side = s;
  }
  return side;
}

}  // namespace dstrans

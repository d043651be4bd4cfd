// Closed meshes that bound a light's reach, drawn to shade only the pixels a point or spot light can
// touch (the thesis, 3.2). A coarse polygon inscribed in a sphere or cone would cut off lit pixels
// near its faces, so these meshes *enclose* the unit sphere / unit cone: every face lies at or outside it.
//
//   dstrans::mesh_data sphere = dstrans::sphere_mesh(1);   // 80 triangles around the unit sphere
//   dstrans::mesh_data cone = dstrans::cone_mesh(16);      // apex at 0, opening along +Z to z = 1, radius 1
//   // scale by the light's range (and tan of the spot angle across the cone), then draw.
#pragma once

#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace dstrans {

// Positions and counter-clockwise (seen from outside) triangles.
struct mesh_data {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;
};

// An icosphere with `subdivisions` (0 to 5) levels, scaled so that it encloses the unit sphere.
inline mesh_data sphere_mesh(int subdivisions) {
  const float t = (1.0f + std::sqrt(5.0f)) * 0.5f;
  mesh_data m;
  for (glm::vec3 v : {glm::vec3(-1, t, 0), glm::vec3(1, t, 0), glm::vec3(-1, -t, 0), glm::vec3(1, -t, 0),
                      glm::vec3(0, -1, t), glm::vec3(0, 1, t), glm::vec3(0, -1, -t), glm::vec3(0, 1, -t),
                      glm::vec3(t, 0, -1), glm::vec3(t, 0, 1), glm::vec3(-t, 0, -1), glm::vec3(-t, 0, 1)})
    m.positions.push_back(glm::normalize(v));
  m.indices = {0, 11, 5, 0, 5, 1,  0, 1, 7,   0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,  11, 10, 2, 10, 7, 6, 7, 1, 8,
               3, 9, 4, 3, 4, 2,  3, 2, 6,   3, 6, 8,  3, 8, 9,   4, 9, 5, 2, 4, 11, 6, 2, 10,  8, 6, 7, 9, 8, 1};
  for (int s = 0; s < subdivisions && s < 5; ++s) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      m.positions.push_back(glm::normalize(m.positions[a] + m.positions[b]));
      return mid[key] = std::uint32_t(m.positions.size() - 1);
    };
    std::vector<std::uint32_t> next;
    for (std::size_t i = 0; i < m.indices.size(); i += 3) {
      const std::uint32_t a = m.indices[i], b = m.indices[i + 1], c = m.indices[i + 2];
      const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    m.indices.swap(next);
  }
  // The faces' planes come closest to the centre; push the nearest one out to distance 1.
  float nearest = 1.0f;
  for (std::size_t i = 0; i < m.indices.size(); i += 3) {
    const glm::vec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]], c = m.positions[m.indices[i + 2]];
    nearest = std::min(nearest, glm::dot(glm::normalize(glm::cross(b - a, c - a)), a));
  }
  for (glm::vec3& p : m.positions) p /= nearest;
  return m;
}

// A cone with its apex at the origin, opening along +Z to a cap at z = 1, enclosing the circular cone of
// radius 1 at z = 1 with `segments` (3 or more) sides.
inline mesh_data cone_mesh(int segments) {
  const int n = segments < 3 ? 3 : segments;
  const float pi = 3.14159265358979f;
  // A regular polygon circumscribes the circle when its corners sit at radius 1 / cos(pi / n).
  const float r = 1.0f / std::cos(pi / float(n));
  mesh_data m;
  m.positions.push_back({0.0f, 0.0f, 0.0f});
  m.positions.push_back({0.0f, 0.0f, 1.0f});
  for (int i = 0; i < n; ++i) {
    const float a = 2.0f * pi * float(i) / float(n);
    m.positions.push_back({r * std::cos(a), r * std::sin(a), 1.0f});
  }
  for (int i = 0; i < n; ++i) {
    const std::uint32_t a = std::uint32_t(2 + i), b = std::uint32_t(2 + (i + 1) % n);
    m.indices.insert(m.indices.end(), {0u, b, a, 1u, a, b});
  }
  return m;
}

}  // namespace dstrans

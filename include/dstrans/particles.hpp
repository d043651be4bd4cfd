// Particle systems as the renderers draw them: where a system's particles are, the
// box its light volume spans, and every particle of a scene as a camera-facing quad, sorted back to front
// for blending over the deferred frame.
//
//   std::vector<dstrans::particle> ps = dstrans::emit(s.particles[0]);
//   auto [lo, hi] = dstrans::particle_bounds(s.particles[0]);      // fit_grid(lo, hi, cells) for its volume
//   std::vector<dstrans::particle_vertex> quads = dstrans::particle_quads(s, s.view);   // 6 vertices a quad
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "scene.hpp"

namespace dstrans {

struct particle {
  glm::vec3 position;
  float size;   // half-width of its quad
  float alpha;  // its share of the material's alpha, (0, 1]
};

// The particles of system `ps`: heights uniform over the plume, positions uniform over its disc at that
// height, sizes from 0.6 to 1.0 of ps.size, alpha from 0.5 to 1.
inline std::vector<particle> emit(const particle_system& ps) {
  std::vector<particle> out;
  detail::random_stream next(ps.seed);
  for (int i = 0; i < ps.count; ++i) {
    const float t = next(), angle = 6.2831853f * next(), r = std::sqrt(next());
    const float spread = ps.radius * (0.25f + 0.75f * t);
    const glm::vec3 p = ps.base + glm::vec3(spread * r * std::cos(angle), ps.height * t, spread * r * std::sin(angle));
    const float size = ps.size * (0.6f + 0.4f * next()), alpha = 0.5f + 0.5f * next();
    out.push_back({p, size, alpha});
  }
  return out;
}

// The box of the particles' centres, where their light volume's cells go: the parts of a quad outside
// it read the nearest cells (dst_volume_texcoord clamps), and cells are not spent below the plume's
// base, which is usually in the floor and in its shadow.
inline std::pair<glm::vec3, glm::vec3> particle_bounds(const particle_system& ps) {
  return {ps.base + glm::vec3(-ps.radius, 0.0f, -ps.radius), ps.base + glm::vec3(ps.radius, ps.height, ps.radius)};
}

// A corner of a particle's quad: world position, the system it belongs to, the corner in [-1, 1]^2
// (right, up as the camera sees it), the particle's alpha share and its size (the quad's half width).
struct particle_vertex {
  glm::vec3 position;
  std::uint32_t system;
  glm::vec2 corner;
  float alpha;
  float size;
};

// Every particle of `s` as two triangles facing camera `c`, the farthest first (by distance along the
// view direction), so that blending each over the frame is back to front across all systems.
inline std::vector<particle_vertex> particle_quads(const scene& s, const camera& c) {
  const glm::mat4 view = c.view();
  const glm::vec3 right(view[0][0], view[1][0], view[2][0]), up(view[0][1], view[1][1], view[2][1]);
  struct placed {
    float depth;
    std::uint32_t system;
    particle p;
  };
  std::vector<placed> all;
  for (std::size_t k = 0; k < s.particles.size(); ++k)
    for (const particle& p : emit(s.particles[k])) all.push_back({(view * glm::vec4(p.position, 1.0f)).z, std::uint32_t(k), p});
  // View space looks down -Z: the most negative z is the farthest. Ties keep emission order.
  std::stable_sort(all.begin(), all.end(), [](const placed& a, const placed& b) { return a.depth < b.depth; });
  std::vector<particle_vertex> out;
  out.reserve(all.size() * 6);
  for (const placed& q : all)
    for (glm::vec2 corner : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
      out.push_back({q.p.position + q.p.size * (corner.x * right + corner.y * up), q.system, corner, q.p.alpha, q.p.size});
  return out;
}

}  // namespace dstrans

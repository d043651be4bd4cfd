// A scene as the renderers take it: procedural shapes placed in the world, materials, lights, a camera.
// Loading a scene file is the caller's business (the dstrans command reads JSON); this header knows no file format.
//
//   dstrans::scene s;
//   s.materials.push_back({{0.2f, 0.6f, 1.0f}, 0.4f, 0.8f, 64.0f, true});              // blue glass
//   s.objects.push_back({dstrans::shape_pane({2.0f, 1.5f}), glm::mat4(1.0f), 0});
//   s.lights.push_back(dstrans::light{});                                                // white sun
//   dstrans::scene_mesh m = dstrans::flatten(s);   // one world-space vertex array for one draw call
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "closed_surface.hpp"
#include "post.hpp"
#include "surface.hpp"

namespace dstrans {

// Triangles with per-vertex normals, counter-clockwise seen from the side the normals point to.
struct shape {
  std::vector<glm::vec3> positions, normals;
  std::vector<std::uint32_t> indices;
  std::vector<glm::vec2> uvs;  // texture coordinates, one a vertex, or none ((0, 0) everywhere)
  std::size_t triangles() const { return indices.size() / 3; }
};

// How texture coordinates outside [0, 1] read a texture: it repeats, its edge texels stretch, or it
// repeats mirrored.
enum class wrap { repeat, clamp, mirror };

// An RGBA8 image that materials sample, rows from the top (as PNG and glTF store them).
struct texture {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // width x height x 4 bytes
  wrap wrap_s = wrap::repeat, wrap_t = wrap::repeat;
  bool valid() const { return width > 0 && height > 0 && rgba.size() == std::size_t(width) * std::size_t(height) * 4u; }
};

struct material {
  glm::vec3 diffuse{0.8f};
  float alpha = 1.0f;            // below 1: transparent
  float spec_intensity = 0.0f;   // [0, 1]
  float spec_power = 16.0f;      // [0, 255]
  bool refractive = false;
  // Many thin layers (hair, fur, dense smoke): drawn into per-pixel lists and resolved by S1's k-buffer
  // instead of the interlaced G-buffer; the shape's normals carry the strand tangents.
  bool hair = false;
  // An index into scene::textures (-1: none): in the G-buffer and forward passes (and the shadow pass, where
  // the material is glass or alpha-tested: render::textured_shadows) its texel at the fragment's texture
  // coordinates multiplies the diffuse colour, and the alpha where the material is transparent or
  // alpha-tested. Texels are taken as stored (dstrans's colours are display values, as its factors are):
  // no sRGB decoding. Hair and particles take the factors alone.
  int texture = -1;
  // Above 0: alpha-tested (glTF's MASK): where the alpha (texel times factor) is below it, no fragment;
  // elsewhere the surface is opaque.
  float alpha_cutoff = 0.0f;
  bool transparent() const { return shader::dst_transparent(alpha) && !(alpha_cutoff > 0.0f) && !hair; }
  // Whether every fragment of it is opaque whatever its texture: neither transparent, alpha-tested nor hair.
  bool opaque() const { return !shader::dst_transparent(alpha) && !(alpha_cutoff > 0.0f) && !hair; }
  // Whether the material samples a texture or tests alpha (effect::textures).
  bool textured() const { return !hair && (texture >= 0 || alpha_cutoff > 0.0f); }
};

enum class light_kind { directional, point, spot };

struct light {
  light_kind kind = light_kind::directional;
  glm::vec3 colour{1.0f};
  float intensity = 1.0f;
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // where a directional or spot light shines
  float range = 10.0f;                     // point and spot: no light at and past this distance
  float inner_angle = 20.0f;               // spot: full light within, degrees from the axis
  float outer_angle = 30.0f;               // spot: no light past, at most 90
  bool shadows = false;                    // from a perspective (spot), orthographic (directional) or cube (point) map
};

struct camera {
  glm::vec3 position{0.0f, 1.5f, 5.0f};
  glm::vec3 target{0.0f, 1.0f, 0.0f};
  float fov_y = 60.0f;  // degrees
  float near_plane = 0.1f, far_plane = 100.0f;

  // +Y is up, except for a camera looking straight up or down (where "up" along the view says nothing):
  // then the image's top points along -Z looking down and +Z looking up, as if the camera had tilted there
  // from looking along -Z.
  glm::vec3 up() const {
    const glm::vec3 d = target - position;
    const float side = glm::length(glm::vec2(d.x, d.z));
    return side > 1e-4f * std::fabs(d.y) ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(0.0f, 0.0f, d.y < 0.0f ? -1.0f : 1.0f);
  }
  glm::mat4 view() const { return glm::lookAtRH(position, target, up()); }
  // Depth 0 at the near plane and 1 at the far plane, clip-space y up: what both backends draw with.
  glm::mat4 projection(float aspect) const {
    return glm::perspectiveRH_ZO(glm::radians(fov_y), aspect, near_plane, far_plane);
  }
};

struct object {
  shape geometry;
  glm::mat4 transform{1.0f};
  std::uint32_t material = 0;  // index into scene::materials
};

// A particle system (S2's smoke): `count` camera-facing quads of half-width `size` in a plume that rises
// `height` above `base`, widening from radius / 4 at the bottom to `radius` at the top; drawn back to front
// with soft alpha (the material's alpha at a quad's centre, fading to 0 at its rim) over the deferred frame
// and lit from a light volume over its bounds. `seed` picks the particles (the same on every machine).
struct particle_system {
  std::uint32_t material = 0;  // index into scene::materials: its diffuse colour and alpha
  glm::vec3 base{0.0f};
  float radius = 0.5f, height = 2.0f, size = 0.25f;
  int count = 100;
  std::uint32_t seed = 1;
};

struct scene {
  std::vector<material> materials;
  std::vector<object> objects;
  std::vector<light> lights;
  camera view;
  glm::vec3 ambient{0.05f};
  std::vector<particle_system> particles;
  std::vector<post_effect> post;  // the post-processing chain after the frame (post.hpp), in order
  std::vector<texture> textures;  // what materials sample (material::texture)
};

// One object's indices in a scene_mesh, `count` from `first`, a sphere that holds its vertices (world
// space), against which a pass culls it (frame/culling.hpp), whether its material is opaque
// (material::opaque: geometry_set::opaque draws it), and whether it is closed: its triangles face out of
// the space they enclose (closed_orientation 1 in world space) and no fragment of it is dropped (not hair,
// not alpha-tested), so that a pass that keeps the nearest surface may cull its back faces.
struct mesh_part {
  std::size_t first = 0, count = 0;
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
  bool opaque = false;
  bool closed = false;
};

// A whole scene in world space, for one draw call: vertex i has positions[i], normals[i], materials[i]
// and, where some shape has texture coordinates, uvs[i] ((0, 0) for shapes without). Objects of hair
// materials come last, from index hair_first on, with tangents for normals. `parts` are the objects, in
// index order.
struct scene_mesh {
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint32_t> materials, indices;
  std::size_t hair_first = 0;
  std::vector<mesh_part> parts;
};

// Whether some shape of `s` has texture coordinates (and flatten gives scene_mesh::uvs).
inline bool has_texture_coordinates(const scene& s) {
  for (const object& o : s.objects)
    if (!o.geometry.uvs.empty()) return true;
  return false;
}

inline scene_mesh flatten(const scene& s) {
  scene_mesh m;
  const bool uvs = has_texture_coordinates(s);
  for (const bool hair : {false, true}) {
    if (hair) m.hair_first = m.indices.size();
    for (const object& o : s.objects) {
      if ((o.material < s.materials.size() && s.materials[o.material].hair) != hair) continue;
      const auto base = std::uint32_t(m.positions.size());
      // Normals are transformed by the inverse transpose; tangents, along the surface, by the matrix itself.
      const glm::mat3 normal_matrix = hair ? glm::mat3(o.transform) : glm::transpose(glm::inverse(glm::mat3(o.transform)));
      glm::vec3 lo(0.0f), hi(0.0f);
      for (std::size_t i = 0; i < o.geometry.positions.size(); ++i) {
        const glm::vec3 p(o.transform * glm::vec4(o.geometry.positions[i], 1.0f));
        lo = i ? glm::min(lo, p) : p;
        hi = i ? glm::max(hi, p) : p;
        m.positions.push_back(p);
        m.normals.push_back(glm::normalize(normal_matrix * o.geometry.normals[i]));
        m.materials.push_back(o.material);
        if (uvs) m.uvs.push_back(i < o.geometry.uvs.size() ? o.geometry.uvs[i] : glm::vec2(0.0f));
      }
      const material* mat = o.material < s.materials.size() ? &s.materials[o.material] : nullptr;
      mesh_part part{m.indices.size(), o.geometry.indices.size(), 0.5f * (lo + hi), 0.0f, mat && mat->opaque()};
      // A mirroring transform turns the triangles' facing round.
      const float handedness = glm::determinant(glm::mat3(o.transform));
      part.closed = !hair && !(mat && mat->alpha_cutoff > 0.0f) &&
                    float(closed_orientation(o.geometry.positions, o.geometry.indices)) * handedness > 0.0f;
      for (std::size_t i = base; i < m.positions.size(); ++i) part.radius = std::max(part.radius, glm::length(m.positions[i] - part.centre));
      for (std::uint32_t i : o.geometry.indices) m.indices.push_back(base + i);
      m.parts.push_back(part);
    }
  }
  return m;
}

namespace detail {
inline void add_quad(shape& s, glm::vec3 origin, glm::vec3 u, glm::vec3 v, glm::vec3 n) {
  const auto base = std::uint32_t(s.positions.size());
  for (glm::vec3 p : {origin, origin + u, origin + u + v, origin + v}) {
    s.positions.push_back(p);
    s.normals.push_back(n);
  }
  s.indices.insert(s.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}
// Revolves a profile of (radius, height) points around +Y with `slices` segments; the normals come from
// the profile's slope. Closed ends where the profile reaches radius 0.
inline shape revolve(const std::vector<glm::vec2>& profile, int slices) {
  shape s;
  const float two_pi = 6.28318530718f;
  for (std::size_t i = 0; i < profile.size(); ++i) {
    const glm::vec2 prev = profile[i == 0 ? 0 : i - 1], next = profile[i + 1 < profile.size() ? i + 1 : i];
    const glm::vec2 tangent = glm::normalize(next - prev);
    const glm::vec2 n2(tangent.y, -tangent.x);  // outward for a profile that goes up
    for (int k = 0; k <= slices; ++k) {
      // The seam's last column repeats the first exactly, so that the surface closes (closed_orientation).
      const float a = two_pi * float(k % slices) / float(slices), c = std::cos(a), sn = std::sin(a);
      s.positions.push_back({profile[i].x * c, profile[i].y, profile[i].x * sn});
      s.normals.push_back(glm::normalize(glm::vec3(n2.x * c, n2.y, n2.x * sn)));
    }
  }
  const auto ring = std::uint32_t(slices + 1);
  for (std::uint32_t i = 0; i + 1 < profile.size(); ++i)
    for (std::uint32_t k = 0; k < std::uint32_t(slices); ++k) {
      const std::uint32_t a = i * ring + k, b = a + 1, c = a + ring, d = c + 1;
      s.indices.insert(s.indices.end(), {a, c, b, b, c, d});
    }
  return s;
}
}  // namespace detail

// A box of `size` centred on the origin.
inline shape shape_box(glm::vec3 size) {
  shape s;
  const glm::vec3 h = size * 0.5f;
  detail::add_quad(s, {-h.x, -h.y, h.z}, {size.x, 0, 0}, {0, size.y, 0}, {0, 0, 1});
  detail::add_quad(s, {h.x, -h.y, -h.z}, {-size.x, 0, 0}, {0, size.y, 0}, {0, 0, -1});
  detail::add_quad(s, {h.x, -h.y, h.z}, {0, 0, -size.z}, {0, size.y, 0}, {1, 0, 0});
  detail::add_quad(s, {-h.x, -h.y, -h.z}, {0, 0, size.z}, {0, size.y, 0}, {-1, 0, 0});
  detail::add_quad(s, {-h.x, h.y, h.z}, {size.x, 0, 0}, {0, 0, -size.z}, {0, 1, 0});
  detail::add_quad(s, {-h.x, -h.y, -h.z}, {size.x, 0, 0}, {0, 0, size.z}, {0, -1, 0});
  return s;
}

// The inside of a box: a room seen from within (normals point inwards), floor at y = 0.
inline shape shape_room(glm::vec3 size) {
  shape s = shape_box(size);
  for (glm::vec3& p : s.positions) p.y += size.y * 0.5f;
  for (glm::vec3& n : s.normals) n = -n;
  for (std::size_t i = 0; i < s.indices.size(); i += 3) std::swap(s.indices[i + 1], s.indices[i + 2]);
  return s;
}

// A rectangle of `size` in the XY plane facing +Z: a pane of glass (transparent materials are lit
// from both sides).
inline shape shape_pane(glm::vec2 size) {
  shape s;
  detail::add_quad(s, {-size.x * 0.5f, -size.y * 0.5f, 0.0f}, {size.x, 0, 0}, {0, size.y, 0}, {0, 0, 1});
  return s;
}

// A sphere of `radius` from `slices` (>= 3) meridians and slices / 2 parallels.
inline shape shape_sphere(float radius, int slices) {
  std::vector<glm::vec2> profile;
  const int stacks = slices / 2 > 2 ? slices / 2 : 2;
  for (int i = 0; i <= stacks; ++i) {
    const float a = 3.14159265359f * float(i) / float(stacks);
    // The poles sit exactly on the axis: sin of a float pi is slightly negative, which would mirror
    // the last ring and turn its triangles inside out.
    const bool pole = i == 0 || i == stacks;
    profile.push_back({pole ? 0.0f : radius * std::sin(a), -radius * std::cos(a)});
  }
  shape s = detail::revolve(profile, slices);
  for (std::size_t i = 0; i < s.positions.size(); ++i) s.normals[i] = glm::normalize(s.positions[i]);
  return s;
}

// A closed cylinder of `radius` and `height` standing on y = 0.
inline shape shape_cylinder(float radius, float height, int slices) {
  return detail::revolve({{0.0f, 0.0f}, {radius, 0.0f}, {radius, 0.0f}, {radius, height}, {radius, height}, {0.0f, height}},
                         slices);
}

// A bottle made on a lathe: body, shoulder, neck and lip, `height` tall, `radius` at the body.
inline shape shape_bottle(float radius, float height, int slices) {
  const float r = radius, h = height;
  return detail::revolve({{0.0f, 0.0f}, {r * 0.9f, 0.0f}, {r, 0.05f * h}, {r, 0.55f * h}, {r * 0.8f, 0.68f * h},
                          {r * 0.35f, 0.78f * h}, {r * 0.3f, 0.95f * h}, {r * 0.38f, h}, {0.0f, h}},
                         slices);
}

namespace detail {
// A PCG-style hash stream in [0, 1): deterministic across compilers and standard libraries.
struct random_stream {
  std::uint32_t state;
  explicit random_stream(std::uint32_t seed) : state(seed * 747796405u + 2891336453u) {}
  float operator()() {
    state = state * 747796405u + 2891336453u;
    std::uint32_t w = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return float((w >> 22u) ^ w) * (1.0f / 4294967296.0f);
  }
};
}  // namespace detail

// Hair: `strands` strands rooted on the upper half of a sphere of `radius` around the origin, each
// `length` long in `segments` pieces, falling under gravity with a little random curl, drawn as two
// crossed ribbons `width` wide so that no view sees them edge-on. Normals hold the strand's tangent
// (material::hair). `seed` picks the strands (the same seed, the same hair on every machine).
inline shape shape_hair(float radius, int strands, float length, float width, int segments, std::uint32_t seed) {
  shape s;
  detail::random_stream next(seed);
  const int n = segments < 1 ? 1 : segments;
  for (int k = 0; k < strands; ++k) {
    const float phi = 6.2831853f * next(), up = 0.15f + 0.85f * next();  // the upper half, not the bottom
    const glm::vec3 root = radius * glm::vec3(std::sqrt(1.0f - up * up) * std::cos(phi), up, std::sqrt(1.0f - up * up) * std::sin(phi));
    glm::vec3 dir = glm::normalize(root), p = root;
    const glm::vec3 curl = glm::normalize(glm::vec3(next() - 0.5f, next() - 0.5f, next() - 0.5f) + glm::vec3(1e-3f));
    std::vector<glm::vec3> points{p};
    for (int i = 0; i < n; ++i) {
      dir = glm::normalize(dir + glm::vec3(0.0f, -0.35f, 0.0f) + 0.2f * curl);
      p += dir * (length / float(n));
      points.push_back(p);
    }
    for (int i = 0; i < n; ++i) {
      const glm::vec3 t = glm::normalize(points[std::size_t(i + 1)] - points[std::size_t(i)]);
      const glm::vec3 a = glm::normalize(glm::cross(t, std::fabs(t.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0)));
      for (glm::vec3 side : {a, glm::normalize(glm::cross(t, a))}) {
        const std::uint32_t base = std::uint32_t(s.positions.size());
        const glm::vec3 h = side * (0.5f * width);
        for (glm::vec3 q : {points[std::size_t(i)] - h, points[std::size_t(i)] + h, points[std::size_t(i + 1)] + h,
                            points[std::size_t(i + 1)] - h}) {
          s.positions.push_back(q);
          s.normals.push_back(t);
        }
        s.indices.insert(s.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
      }
    }
  }
  return s;
}

}  // namespace dstrans

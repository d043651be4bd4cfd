// The example engines' world at step 4, as the description dstrans's renderer is made from: their floor,
// red box and two panes, now with hair, smoke, a sun beside the spot light, and an anti-aliasing pass.
// examples/scenes/engine_world.json is the same scene as a file (`dstrans render` draws the same image);
// the engines draw these objects from their own vertex buffers.
#pragma once

#include <glm/gtc/matrix_transform.hpp>

#include <dstrans/scene.hpp>

namespace example {

// Placed as a scene file places an object: moved to `position`, then turned `yaw` degrees about +Y.
inline glm::mat4 placed(glm::vec3 position, float yaw = 0.0f) {
  return glm::rotate(glm::rotate(glm::translate(glm::mat4(1.0f), position), glm::radians(yaw), glm::vec3(0, 1, 0)), 0.0f,
                     glm::vec3(1, 0, 0));
}

inline dstrans::scene engine_world() {
  dstrans::scene s;
  s.view.position = {0.0f, 1.6f, 3.6f};
  s.view.target = {0.0f, 0.5f, 0.0f};
  s.view.fov_y = 55.0f;
  s.view.near_plane = 0.1f;
  s.view.far_plane = 30.0f;
  s.ambient = glm::vec3(0.08f);
  auto material = [](glm::vec3 diffuse, float alpha, float spec, float power, bool refractive, bool hair) {
    dstrans::material m;
    m.diffuse = diffuse;
    m.alpha = alpha;
    m.spec_intensity = spec;
    m.spec_power = power;
    m.refractive = refractive;
    m.hair = hair;
    return m;
  };
  s.materials = {material(glm::vec3(0.8f), 1.0f, 0.0f, 16.0f, false, false),
                 material({0.8f, 0.2f, 0.1f}, 1.0f, 0.5f, 32.0f, false, false),
                 material({0.2f, 0.5f, 1.0f}, 0.4f, 0.9f, 64.0f, true, false),
                 material({0.2f, 1.0f, 0.3f}, 0.5f, 0.9f, 64.0f, true, false),
                 material({0.55f, 0.35f, 0.18f}, 0.3f, 0.0f, 16.0f, false, true),
                 material({0.7f, 0.7f, 0.75f}, 0.25f, 0.0f, 16.0f, false, false)};
  s.objects = {{dstrans::shape_box({8.0f, 0.1f, 8.0f}), placed({0.0f, -0.05f, 0.0f}), 0},
               {dstrans::shape_box({0.6f, 0.6f, 0.6f}), placed({0.6f, 0.3f, -1.0f}), 1},
               {dstrans::shape_pane({1.4f, 1.0f}), placed({-0.3f, 0.6f, 0.3f}), 2},
               {dstrans::shape_pane({0.8f, 0.8f}), placed({1.0f, 0.5f, 0.8f}, 28.6479f), 3},
               {dstrans::shape_hair(0.25f, 600, 0.5f, 0.012f, 6, 3), placed({-1.2f, 0.0f, -0.6f}), 4}};
  dstrans::light spot;
  spot.kind = dstrans::light_kind::spot;
  spot.position = {-1.0f, 3.5f, 2.5f};
  spot.direction = glm::normalize(glm::vec3(0.4f, -1.0f, -0.9f));
  spot.colour = {1.6f, 1.5f, 1.4f};
  spot.range = 12.0f;
  spot.inner_angle = 30.0f;
  spot.outer_angle = 36.87f;
  spot.shadows = true;
  dstrans::light sun;
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.2f));
  sun.colour = {0.5f, 0.55f, 0.6f};
  sun.intensity = 0.4f;
  s.lights = {spot, sun};
  dstrans::particle_system smoke;
  smoke.material = 5;
  smoke.base = {0.2f, 0.0f, -0.4f};
  smoke.radius = 0.4f;
  smoke.height = 1.2f;
  smoke.size = 0.2f;
  smoke.count = 60;
  smoke.seed = 5;
  s.particles = {smoke};
  dstrans::post_effect aa;
  aa.kind = dstrans::post_kind::antialias;
  s.post = {aa};
  return s;
}

// The scene's vertex of one object as the engines keep it for dstrans: in world space, because dstrans's
// geometry passes take positions as they come (its vertex contract has no model matrix yet).
struct world_vertex {
  glm::vec3 position, normal;
};
inline std::vector<world_vertex> world_vertices(const dstrans::scene& s, const dstrans::object& o) {
  const bool hair = s.materials[o.material].hair;
  // Normals are transformed by the inverse transpose; tangents, along the surface, by the matrix itself.
  const glm::mat3 n = hair ? glm::mat3(o.transform) : glm::transpose(glm::inverse(glm::mat3(o.transform)));
  std::vector<world_vertex> out;
  for (std::size_t i = 0; i < o.geometry.positions.size(); ++i)
    out.push_back({glm::vec3(o.transform * glm::vec4(o.geometry.positions[i], 1.0f)), glm::normalize(n * o.geometry.normals[i])});
  return out;
}

}  // namespace example

// A ladder of scenes that call for one effect more at each step: a room lit by a shadowed spot
// light and the sun; then a glass pane out of the spot's cone; then the pane refractive; then the spot
// turned to the pane; then a column of smoke; then a chequered texture on the floor. Without shadows at
// step 0 the scene calls for nothing.
#pragma once

#include <set>
#include <string>

#include <dstrans/scene.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace dstrans::testing {

// What one rung's plan has and the other's has not (switches, targets, effects by name).
inline std::set<std::string> minus(const std::set<std::string>& a, const std::set<std::string>& b) {
  std::set<std::string> out;
  for (const std::string& x : a)
    if (!b.count(x)) out.insert(x);
  return out;
}

enum class rung { nothing, shadows, glass, refractive, seen, particles, textured };
constexpr rung all_rungs[] = {rung::nothing, rung::shadows, rung::glass, rung::refractive, rung::seen, rung::particles, rung::textured};

// A chequer of `n` x `n` squares of `side` texels each, alternating `a` and `b` (RGBA), from the top left.
inline texture chequer(int n, int side, glm::u8vec4 a, glm::u8vec4 b) {
  texture t;
  t.width = t.height = n * side;
  for (int y = 0; y < t.height; ++y)
    for (int x = 0; x < t.width; ++x) {
      const glm::u8vec4 c = ((x / side) + (y / side)) % 2 ? b : a;
      t.rgba.insert(t.rgba.end(), {c.r, c.g, c.b, c.a});
    }
  return t;
}

inline scene effect_scene(rung r) {
  scene s;
  s.view.position = {0.0f, 1.5f, 5.0f};
  s.view.target = {0.0f, 1.0f, 0.0f};
  s.materials.push_back({glm::vec3(0.8f), 1.0f, 0.2f, 16.0f, false});                       // floor
  s.materials.push_back({glm::vec3(0.8f, 0.2f, 0.1f), 1.0f, 0.5f, 32.0f, false});           // red box
  s.materials.push_back({glm::vec3(0.2f, 0.5f, 1.0f), 0.4f, 0.9f, 64.0f, r >= rung::refractive});  // glass
  s.objects.push_back({shape_box({8.0f, 0.02f, 8.0f}), glm::translate(glm::mat4(1.0f), {0.0f, 0.01f, 0.0f}), 0});
  if (r >= rung::textured) {
    s.textures.push_back(chequer(2, 4, {255, 255, 255, 255}, {90, 140, 200, 255}));
    s.materials[0].texture = 0;
    for (const glm::vec3& p : s.objects[0].geometry.positions) s.objects[0].geometry.uvs.emplace_back(p.x, p.z);  // a texture a metre
  }
  s.objects.push_back({shape_box({0.6f, 0.8f, 0.6f}), glm::translate(glm::mat4(1.0f), {1.0f, 0.4f, -1.0f}), 1});
  if (r >= rung::glass)
    s.objects.push_back({shape_pane({1.2f, 1.0f}), glm::translate(glm::mat4(1.0f), {-1.2f, 1.0f, 0.5f}), 2});
  light sun;
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.2f));
  sun.intensity = 0.3f;
  light spot;
  spot.kind = light_kind::spot;
  spot.position = {2.0f, 3.0f, 0.0f};
  spot.direction = glm::normalize(r >= rung::seen ? glm::vec3(-3.2f, -2.0f, 0.5f) : glm::vec3(-0.5f, -3.0f, -1.0f));
  spot.range = 8.0f;
  spot.inner_angle = 15.0f;
  spot.outer_angle = 25.0f;
  spot.intensity = 1.5f;
  spot.shadows = r >= rung::shadows;
  s.lights = {sun, spot};
  if (r >= rung::particles) {
    s.materials.push_back({glm::vec3(0.9f), 0.4f, 0.0f, 16.0f, false});  // smoke
    particle_system smoke;
    smoke.material = 3;
    smoke.base = {0.2f, 0.0f, 0.3f};
    smoke.radius = 0.4f;
    smoke.height = 1.5f;
    smoke.count = 60;
    s.particles.push_back(smoke);
  }
  return s;
}

}  // namespace dstrans::testing

// Which effects a scene calls for, and why: a scene without glass must cost what
// a plain deferred renderer costs, so every effect is derived from the scene, never assumed.
//
//   std::vector<dstrans::feature> found = dstrans::scene_features(s);
//   // {transparency, "objects[3] has material 2 with alpha 0.35"}, {shadows, "lights[0] is a spot light ..."}
//   dstrans::effects e = dstrans::effects_of(found);
//   if (e.has(dstrans::effect::refraction)) { ... }
//   constexpr dstrans::effects glass = dstrans::effect_set<dstrans::effect::transparency>::value;
//
// The effects and what calls for each:
// - transparency: an object whose material has alpha below 1 (interlaced G-buffer, de-interlacing);
// - refraction: such an object whose material is refractive;
// - shadows: a spot or directional light that casts shadows (shadow pass, depth map, lookup);
// - transparent_shadows: such a light that reaches a transparent object (the shadow map's colour target and
//   the lookup of Eq. 3.1): a directional light reaches every object, a spot light those whose bounding
//   sphere meets its cone and range, so it is conservative: an occluded pane still counts;
// - many_layers: an object whose material is hair (per-pixel lists and the k-buffer resolve of S1);
// - light_volumes: a particle system with particles (S2: the bake into a 3D texture, the particle pass);
// - textures: an object whose material samples a texture or is alpha-tested (texture coordinates in the
//   geometry passes, the scene's textures as one array).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene.hpp"

namespace dstrans {

enum class effect : unsigned { transparency, refraction, shadows, transparent_shadows, many_layers, light_volumes, textures };
constexpr effect all_effects[] = {effect::transparency, effect::refraction,    effect::shadows, effect::transparent_shadows,
                                  effect::many_layers,  effect::light_volumes, effect::textures};

// The effect's name in plans and reports.
constexpr const char* effect_name(effect e) {
  switch (e) {
    case effect::transparency: return "transparency";
    case effect::refraction: return "refraction";
    case effect::shadows: return "shadows";
    case effect::transparent_shadows: return "transparent_shadows";
    case effect::many_layers: return "many_layers";
    case effect::light_volumes: return "light_volumes";
    case effect::textures: return "textures";
  }
  return "";
}

// The preprocessor switch that pass shaders test with #ifdef for the effect.
constexpr const char* effect_switch(effect e) {
  switch (e) {
    case effect::transparency: return "DST_TRANSPARENCY";
    case effect::refraction: return "DST_REFRACTION";
    case effect::shadows: return "DST_SHADOWS";
    case effect::transparent_shadows: return "DST_TRANSPARENT_SHADOWS";
    case effect::many_layers: return "DST_MANY_LAYERS";
    case effect::light_volumes: return "DST_LIGHT_VOLUMES";
    case effect::textures: return "DST_TEXTURES";
  }
  return "";
}

// A set of effects.
struct effects {
  unsigned bits = 0;

  constexpr bool has(effect e) const { return (bits >> unsigned(e)) & 1u; }
  constexpr effects with(effect e) const { return {bits | (1u << unsigned(e))}; }
  constexpr effects without(effect e) const { return {bits & ~(1u << unsigned(e))}; }
  constexpr bool operator==(effects o) const { return bits == o.bits; }
  constexpr bool operator!=(effects o) const { return bits != o.bits; }
  // Every effect, in the order of all_effects.
  static constexpr effects all() { return {(1u << 7) - 1u}; }
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (effect e : all_effects)
      if (has(e)) out.push_back(effect_name(e));
    return out;
  }
};

// A set fixed at compile time: effect_set<effect::transparency, effect::refraction>::value.
template <effect... E>
struct effect_set {
  static constexpr effects value{(0u | ... | (1u << unsigned(E)))};
};

// An effect a scene calls for, with the reason in words.
struct feature {
  effect what;
  std::string why;
};

namespace detail {
// The centre and radius of a sphere around object o's vertices, in world space.
inline std::pair<glm::vec3, float> bounding_sphere(const object& o) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec3& p : o.geometry.positions) {
    const glm::vec3 w = glm::vec3(o.transform * glm::vec4(p, 1.0f));
    lo = glm::min(lo, w);
    hi = glm::max(hi, w);
  }
  if (o.geometry.positions.empty()) return {glm::vec3(0.0f), -1.0f};
  const glm::vec3 c = (lo + hi) * 0.5f;
  float r = 0.0f;
  for (const glm::vec3& p : o.geometry.positions) r = std::max(r, glm::length(glm::vec3(o.transform * glm::vec4(p, 1.0f)) - c));
  return {c, r};
}

// Whether light l reaches the sphere at `c` of radius `r` (negative: an object without vertices).
inline bool reaches(const light& l, glm::vec3 c, float r) {
  if (r < 0.0f) return false;
  if (l.kind == light_kind::directional) return true;
  const glm::vec3 v = c - l.position;
  const float distance = glm::length(v);
  if (distance <= r) return true;
  if (distance - r >= l.range) return false;
  if (l.kind == light_kind::point) return true;
  const float axis = glm::dot(v / distance, glm::normalize(l.direction));
  const float angle = std::acos(std::clamp(axis, -1.0f, 1.0f));
  const float spread = std::asin(std::min(r / distance, 1.0f));
  return angle - spread < glm::radians(l.outer_angle);
}

// The bounding spheres of s's transparent objects, with their indices in s.objects: computed once for
// every light they are tested against, as each walks all of an object's vertices.
struct placed_sphere {
  std::size_t object;
  glm::vec3 centre;
  float radius;
};
inline std::vector<placed_sphere> transparent_spheres(const scene& s) {
  std::vector<placed_sphere> out;
  for (std::size_t k = 0; k < s.objects.size(); ++k) {
    const object& o = s.objects[k];
    if (o.material >= s.materials.size() || !s.materials[o.material].transparent()) continue;
    const auto [c, r] = bounding_sphere(o);
    out.push_back({k, c, r});
  }
  return out;
}

// The first of `spheres` light l reaches, or null.
inline const placed_sphere* first_reached(const light& l, const std::vector<placed_sphere>& spheres) {
  for (const placed_sphere& p : spheres)
    if (reaches(l, p.centre, p.radius)) return &p;
  return nullptr;
}
}  // namespace detail

// Whether light l reaches object o's bounding sphere: a directional light reaches every object, a point
// light those within its range, a spot light those within its cone (outer angle) and range.
inline bool light_reaches(const light& l, const object& o) {
  const auto [c, r] = detail::bounding_sphere(o);
  return detail::reaches(l, c, r);
}

// Whether light l casts shadows the renderer draws: spot lights (as in the thesis) from a perspective map,
// directional lights from an orthographic one over the scene's bounds, point lights from a cube of six
// perspective maps.
inline bool casts_shadows(const light& l) { return l.shadows; }

// Whether the shadow map of light l must hold transparent occluders: it casts shadows and reaches a
// transparent object of s.
inline bool sees_transparency(const scene& s, const light& l) {
  return casts_shadows(l) && detail::first_reached(l, detail::transparent_spheres(s)) != nullptr;
}

// The effects scene s calls for, each once, with the first reason found.
inline std::vector<feature> scene_features(const scene& s) {
  std::vector<feature> out;
  auto add = [&](effect e, const std::string& why) {
    for (const feature& f : out)
      if (f.what == e) return;
    out.push_back({e, why});
  };
  auto number = [](float v) {
    std::string t = std::to_string(v);
    t.erase(t.find_last_not_of('0') + 1);
    if (t.back() == '.') t.pop_back();
    return t;
  };
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    const std::uint32_t m = s.objects[i].material;
    if (m < s.materials.size() && s.materials[m].hair)
      add(effect::many_layers, "objects[" + std::to_string(i) + "] has material " + std::to_string(m) + ", which is hair");
    if (m < s.materials.size() && s.materials[m].textured()) {
      const material& t = s.materials[m];
      add(effect::textures, "objects[" + std::to_string(i) + "] has material " + std::to_string(m) +
                                (t.texture >= 0 ? ", which samples textures[" + std::to_string(t.texture) + "]"
                                                : ", alpha-tested at " + number(t.alpha_cutoff)));
    }
    if (m >= s.materials.size() || !s.materials[m].transparent()) continue;
    const std::string what = "objects[" + std::to_string(i) + "] has material " + std::to_string(m) + " with alpha " +
                             number(s.materials[m].alpha);
    add(effect::transparency, what);
    if (s.materials[m].refractive) add(effect::refraction, what + ", refractive");
  }
  for (std::size_t i = 0; i < s.particles.size(); ++i)
    if (s.particles[i].count > 0)
      add(effect::light_volumes, "particles[" + std::to_string(i) + "] draws " + std::to_string(s.particles[i].count) +
                                     " particles of material " + std::to_string(s.particles[i].material));
  std::optional<std::vector<detail::placed_sphere>> spheres;
  bool transparent_shadows = false;
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    const light& l = s.lights[i];
    if (!casts_shadows(l)) continue;
    const char* kind = l.kind == light_kind::spot ? "spot" : l.kind == light_kind::point ? "point" : "directional";
    add(effect::shadows, "lights[" + std::to_string(i) + "] is a " + kind + " light that casts shadows");
    if (transparent_shadows) continue;  // only the first reason is kept
    if (!spheres) spheres = detail::transparent_spheres(s);
    if (const detail::placed_sphere* p = detail::first_reached(l, *spheres)) {
      add(effect::transparent_shadows, "lights[" + std::to_string(i) + "] casts shadows and reaches objects[" +
                                           std::to_string(p->object) + "], which is transparent");
      transparent_shadows = true;
    }
  }
  std::sort(out.begin(), out.end(), [](const feature& a, const feature& b) { return a.what < b.what; });
  return out;
}

// The set of the features' effects.
inline effects effects_of(const std::vector<feature>& found) {
  effects e;
  for (const feature& f : found) e = e.with(f.what);
  return e;
}

}  // namespace dstrans

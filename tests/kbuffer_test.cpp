// S1's shared formulas on the CPU: the node's fields round-trip, Eq. 2 behaves as a strand, the
// tail blend is exact for one fragment and order-independent, and the hair shape is what its seed says.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

#include <dstrans/kbuffer.hpp>
#include <dstrans/scene.hpp>
#include <dstrans/scene_features.hpp>

using namespace dstrans;
using namespace dstrans::shader;

TEST_CASE("a tangent survives the node's 32 bits within 0.01 degrees, colours within half a code", "[kbuffer]") {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  float worst = 0.0f;
  for (int i = 0; i < 100000; ++i) {
    glm::vec3 t(u(rng), u(rng), u(rng));
    if (glm::dot(t, t) < 1e-4f) continue;
    t = glm::normalize(t);
    const glm::vec3 back = dst_unpack_tangent(dst_pack_tangent(t));
    worst = std::max(worst, 2.0f * std::asin(glm::length(t - back) * 0.5f));  // acos loses digits near 0
  }
  CHECK(glm::degrees(worst) < 0.01f);
  for (glm::vec3 axis : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(1, 0, 0), glm::vec3(0, -1, 0)})
    CHECK(glm::length(dst_unpack_tangent(dst_pack_tangent(axis)) - axis) < 1e-4f);
  CHECK(dst_octahedral_encode(glm::vec3(0.0f)) == glm::vec2(0.0f));  // no direction: the +Z code
  const glm::vec4 c(0.2f, 0.5f, 1.0f, 0.3f);
  CHECK(glm::all(glm::lessThanEqual(glm::abs(dst_unpack_colour(dst_pack_colour(c)) - c), glm::vec4(0.5f / 255.0f + 1e-6f))));
}

TEST_CASE("Eq. 2 shades a strand: no light along the tangent, full diffuse across it, specular peaks", "[kbuffer]") {
  const glm::vec3 t(1, 0, 0), colour(0.6f, 0.4f, 0.2f), light(1.0f);
  CHECK(dst_hair_cheap(t, t, colour, light, 1.0f) == glm::vec3(0.0f));                   // sin(T, L) = 0
  CHECK(glm::length(dst_hair_cheap(t, {0, 1, 0}, colour, light, 1.0f) - colour) < 1e-6f);  // sin = 1
  CHECK(dst_hair_cheap(t, {0, 1, 0}, colour, light, 0.0f) == glm::vec3(0.0f));            // fully shadowed
  const glm::vec3 l(0, 1, 0), v(0, 1, 0);
  const glm::vec3 full = dst_hair_full(t, l, v, colour, light, 1.0f);
  CHECK(glm::all(glm::greaterThan(full, dst_hair_cheap(t, l, colour, light, 1.0f))));  // the lobes add light
  CHECK(dst_hair_full(t, l, v, colour, light, 0.5f) == full * 0.5f);                      // visibility scales all
  CHECK(dst_strand_specular(t, t, 20.0f) == 0.0f);          // H along the tangent: no lobe
  CHECK(dst_strand_specular(t, {0, 1, 0}, 80.0f) == 1.0f);  // H across it: the peak
  CHECK(dst_hair_full(glm::vec3(NAN), l, v, colour, light, 1.0f) == glm::vec3(0.0f));
}

// T T^T's diagonal and its xy, xz, yz, weighted by `w`, added to `diag` and `off`.
static void gather(glm::vec3& diag, glm::vec3& off, glm::vec3 t, float w) {
  diag += w * t * t;
  off += w * glm::vec3(t.x * t.y, t.x * t.z, t.y * t.z);
}

TEST_CASE("the tail shaded at once: one fragment as dst_hair_cheap, many near their mean, never NaN", "[kbuffer]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const glm::vec3 colour(0.6f, 0.4f, 0.2f), light(1.5f, 1.0f, 0.5f);
  double worst_one = 0.0, worst_many = 0.0;
  for (int trial = 0; trial < 1000; ++trial) {
    const glm::vec3 l = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(1e-3f));
    glm::vec3 diag(0.0f), off(0.0f), each(0.0f);
    float alphas = 0.0f;
    const int n = 1 + trial % 12;
    for (int i = 0; i < n; ++i) {
      const glm::vec3 t = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(1e-3f));
      const float a = 0.2f + 0.3f * (u(rng) + 1.0f);
      gather(diag, off, t, a);
      each += a * dst_hair_cheap(t, l, colour, light, 0.7f);
      alphas += a;
    }
    const glm::vec3 once = dst_hair_cheap_mean(diag / alphas, off / alphas, l, colour * alphas, light, 0.7f);
    const double error = glm::length(once - each) / glm::length(colour * light * alphas);
    if (n == 1) worst_one = std::max(worst_one, error);
    else {
      CHECK(glm::all(glm::greaterThanEqual(once, each - glm::vec3(1e-4f))));  // Jensen: never darker
      worst_many = std::max(worst_many, error);
    }
  }
  CHECK(worst_one < 1e-5);
  // sqrt(E[s^2]) - E[s] for sines in [0, 1] is at most 1/4 (s 0 or 1: sqrt(p) - p), here times visibility 0.7.
  CHECK(worst_many <= 0.25 * 0.7 + 1e-4);
  // Two tangents across L (sin 1) and along it (sin 0), alike: the root of the mean sin^2, sqrt(1/2).
  glm::vec3 diag(0.0f), off(0.0f);
  gather(diag, off, {1, 0, 0}, 0.5f);
  gather(diag, off, {0, 1, 0}, 0.5f);
  CHECK(glm::length(dst_hair_cheap_mean(diag, off, {0, 1, 0}, glm::vec3(1.0f), glm::vec3(1.0f), 1.0f) - glm::vec3(std::sqrt(0.5f))) < 1e-6f);
  CHECK(dst_hair_cheap_mean(glm::vec3(NAN), off, {0, 1, 0}, colour, light, 1.0f) == glm::vec3(0.0f));
  CHECK(dst_hair_cheap_mean(diag, glm::vec3(INFINITY), {0, 1, 0}, colour, light, 1.0f) == glm::vec3(0.0f));
  CHECK(dst_hair_cheap_mean(diag, off, glm::vec3(NAN), colour, light, 1.0f) == glm::vec3(0.0f));
  CHECK(dst_hair_cheap_mean(diag, off, {0, 1, 0}, colour, light, NAN) == glm::vec3(0.0f));
  CHECK(dst_hair_cheap_mean({0, 2, 0}, off, {0, 1, 0}, colour, light, 1.0f) == glm::vec3(0.0f));  // past 1: none, not NaN
}

TEST_CASE("Eq. 1's term: no occluder lets all light through, an opaque one none", "[kbuffer]") {
  CHECK(dst_hair_transmittance(0.3f, 8.0f, 0.0f) == 1.0f);
  CHECK(dst_hair_transmittance(0.3f, 8.0f, -1.0f) == 1.0f);
  CHECK(dst_hair_transmittance(1.0f, 8.0f, 0.5f) == 0.0f);
  CHECK(dst_hair_transmittance(0.5f, 2.0f, 1.0f) == Approx(0.25f));
  CHECK(dst_shadow_tap_weight(0.0f, 0.0f) == 1.0f);
  CHECK(dst_shadow_tap_weight(1.0f, 1.0f) == Approx(std::exp(-1.0f)));
}

TEST_CASE("the tail is exact for one fragment and the same in any order", "[kbuffer]") {
  const glm::vec3 background(0.1f, 0.2f, 0.3f);
  const glm::vec4 one(0.9f, 0.5f, 0.1f, 0.4f);
  const glm::vec3 exact = dst_over(background, one);
  const glm::vec3 tail = dst_tail_over(background, dst_tail_add(glm::vec4(0.0f), one), 1.0f - one.w);
  CHECK(glm::length(tail - exact) < 1e-6f);
  std::vector<glm::vec4> layers{{1, 0, 0, 0.3f}, {0, 1, 0, 0.5f}, {0, 0, 1, 0.2f}, {1, 1, 0, 0.7f}};
  auto blend = [&] {
    glm::vec4 acc(0.0f);
    float transmittance = 1.0f;
    for (const glm::vec4& l : layers) {
      acc = dst_tail_add(acc, l);
      transmittance *= 1.0f - l.w;
    }
    return dst_tail_over(background, acc, transmittance);
  };
  const glm::vec3 a = blend();
  std::reverse(layers.begin(), layers.end());
  CHECK(glm::length(blend() - a) < 1e-6f);
  CHECK(dst_tail_over(background, glm::vec4(0.0f), 1.0f) == background);  // an empty tail
  CHECK(dst_wboit_resolve(background, glm::vec4(0.0f), 1.0f) == background);
  CHECK(dst_wboit_weight(1.0f, 0.0f) == 3000.0f);
  CHECK(dst_wboit_weight(0.0f, 0.5f) == 0.01f);
  CHECK(dst_wboit_weight(NAN, 0.5f) == 0.01f);
}

TEST_CASE("hair: strands of crossed ribbons whose normals are tangents, the same for the same seed", "[kbuffer][scene]") {
  const shape h = shape_hair(0.5f, 10, 1.0f, 0.01f, 4, 7);
  CHECK(h.triangles() == 10u * 4u * 2u * 2u);
  for (const glm::vec3& n : h.normals) CHECK(glm::length(n) == Approx(1.0f));
  const shape again = shape_hair(0.5f, 10, 1.0f, 0.01f, 4, 7), other = shape_hair(0.5f, 10, 1.0f, 0.01f, 4, 8);
  CHECK(again.positions == h.positions);
  CHECK(other.positions != h.positions);
  for (std::size_t i = 0; i < h.positions.size(); i += 16) CHECK(glm::length(h.positions[i]) >= 0.49f);  // roots on the scalp
  scene s;
  s.materials = {material{}, material{}};
  s.materials[1].hair = true;
  s.materials[1].alpha = 0.3f;
  s.objects = {{h, glm::mat4(1.0f), 1}};
  const auto found = scene_features(s);
  REQUIRE(found.size() == 1);
  CHECK(found[0].what == effect::many_layers);  // hair is not the interlaced single layer
  CHECK(found[0].why == "objects[0] has material 1, which is hair");
}

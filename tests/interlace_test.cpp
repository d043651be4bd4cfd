// Interlace predicates: the parity rules, and partners at every edge and size.
#include <catch2/catch.hpp>

#include <dstrans/interlace.hpp>

using namespace dstrans;

namespace {
// Checks every pixel of every image up to 9x9; `has_partner(w, h)` says where a partner must exist.
template <class I>
void check_partners(bool (*has_partner)(int w, int h)) {
  for (int w = 1; w <= 9; ++w)
    for (int h = 1; h <= 9; ++h)
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const glm::ivec2 p{x, y}, size{w, h}, q = I::partner(p, size);
          INFO(I::name << " size " << w << "x" << h << " pixel " << x << "," << y);
          REQUIRE(q.x >= 0);
          REQUIRE(q.y >= 0);
          REQUIRE(q.x < w);
          REQUIRE(q.y < h);
          if (has_partner(w, h)) {
            // The other layer always lives on a pixel of the other kind, one step away.
            REQUIRE(I::keep(q, size) != I::keep(p, size));
            REQUIRE(std::abs(q.x - p.x) + std::abs(q.y - p.y) == 1);
          } else {
            REQUIRE(q == p);
          }
        }
}
}  // namespace

TEST_CASE("rows: odd rows keep transparency, the partner is the row above", "[interlace]") {
  using I = interlace::rows;
  CHECK_FALSE(I::keep({0, 0}, {4, 4}));
  CHECK(I::keep({3, 1}, {4, 4}));
  CHECK_FALSE(I::keep({3, 2}, {4, 4}));
  CHECK(I::partner({2, 3}, {4, 4}) == glm::ivec2(2, 2));
  CHECK(I::partner({2, 0}, {4, 4}) == glm::ivec2(2, 1));  // row 0 has nothing above
  CHECK(I::partner({2, 4}, {4, 5}) == glm::ivec2(2, 3));  // last row of an odd height
  CHECK(I::partner({2, 0}, {4, 1}) == glm::ivec2(2, 0));  // a 1-row image has no partner
  check_partners<I>([](int, int h) { return h >= 2; });
}

TEST_CASE("columns: odd columns keep transparency, the partner is the column to the left", "[interlace]") {
  using I = interlace::columns;
  CHECK(I::keep({1, 0}, {4, 4}));
  CHECK_FALSE(I::keep({2, 3}, {4, 4}));
  CHECK(I::partner({0, 2}, {4, 4}) == glm::ivec2(1, 2));
  CHECK(I::partner({3, 2}, {4, 4}) == glm::ivec2(2, 2));
  check_partners<I>([](int w, int) { return w >= 2; });
}

TEST_CASE("checker: x + y odd keeps transparency; the partner is a 4-neighbour", "[interlace]") {
  using I = interlace::checker;
  CHECK(I::keep({1, 0}, {4, 4}));
  CHECK(I::keep({0, 1}, {4, 4}));
  CHECK_FALSE(I::keep({1, 1}, {4, 4}));
  CHECK(I::partner({0, 0}, {4, 4}) == glm::ivec2(1, 0));
  CHECK(I::partner({0, 3}, {1, 4}) == glm::ivec2(0, 2));  // 1 pixel wide: vertical partner
  CHECK(I::partner({0, 0}, {1, 1}) == glm::ivec2(0, 0));
  check_partners<I>([](int w, int h) { return w >= 2 || h >= 2; });
}

TEST_CASE("none: every pixel keeps transparency and is its own partner", "[interlace]") {
  using I = interlace::none;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) {
      CHECK(I::keep({x, y}, {3, 3}));
      CHECK(I::partner({x, y}, {3, 3}) == glm::ivec2(x, y));
    }
}

// The edge-aware reconstruction's two formulas.
TEST_CASE("reconstruction returns a constant layer exactly and adds nothing across an edge", "[interlace][reconstruct]") {
  using shader::dst_layer_similarity;
  using shader::dst_reconstruct;
  const glm::vec3 up(0, 1, 0), side(1, 0, 0);
  // The same surface: full weight; the other layer class, a depth step of 10%, a fold: none.
  CHECK(dst_layer_similarity(0.9f, up, 1.0f, 0.9f, up, 1.0f) == 1.0f);
  CHECK(dst_layer_similarity(0.9f, up, 0.4f, 0.9f, up, 1.0f) == 0.0f);
  CHECK(dst_layer_similarity(0.9f, up, 1.0f, 0.91f, up, 1.0f) == 0.0f);  // 1 - 0.91 = 0.09: a step of 11%
  CHECK(dst_layer_similarity(0.9f, up, 1.0f, 0.9f, side, 1.0f) == 0.0f);
  CHECK(dst_layer_similarity(0.9f, up, 1.0f, 0.9004f, up, 1.0f) > 0.9f);  // 0.4% farther: the same surface
  CHECK(dst_layer_similarity(1.0f, up, 1.0f, 1.0f, up, 1.0f) == 1.0f);    // both the cleared background
  // A constant layer comes back bit for bit, whatever the weights.
  for (const glm::vec4 v : {glm::vec4(0.1f, 0.2f, 0.3f, 0.7f), glm::vec4(0.999f), glm::vec4(1e-7f)})
    for (const glm::vec3 w : {glm::vec3(1.0f), glm::vec3(0.3f, 1.0f, 0.0f), glm::vec3(0.0f)}) CHECK(dst_reconstruct(v, v, v, v, w) == v);
  // A neighbour across an edge (weight 0) adds nothing; one on the same surface is averaged in.
  const glm::vec4 near(1, 0, 0, 1), far(0, 1, 0, 1);
  CHECK(dst_reconstruct(near, far, far, far, glm::vec3(0.0f)) == near);
  CHECK(dst_reconstruct(near, near * 0.5f, far, far, glm::vec3(1.0f, 0.0f, 0.0f)) == glm::vec4(0.75f, 0, 0, 0.75f));
  CHECK(dst_reconstruct(near, far, far, far, glm::vec3(std::nanf(""))) == near);
}

TEST_CASE("a history sample takes in its neighbours linearly, by distance and only on the same surface", "[interlace][temporal]") {
  using shader::dst_history_shares;
  // On the pixel's ray and on the previous frame's pixel centre: the sample alone.
  CHECK(dst_history_shares(glm::vec2(0.0f), glm::vec2(1.0f)) == glm::vec2(0.0f));
  // Half a pixel across: half the neighbour; a pixel along: this frame's sample one pixel the other way
  // is as near, so half; a quarter along: 0.25 / 1.25 of it.
  CHECK(dst_history_shares(glm::vec2(-0.5f, 1.0f), glm::vec2(1.0f)) == glm::vec2(0.5f, 0.5f));
  CHECK(dst_history_shares(glm::vec2(0.0f, 0.25f), glm::vec2(1.0f)).y == Approx(0.2f));
  // Another surface shares nothing, a partly similar one in proportion.
  CHECK(dst_history_shares(glm::vec2(0.5f, 0.5f), glm::vec2(0.0f)) == glm::vec2(0.0f));
  CHECK(dst_history_shares(glm::vec2(0.5f, 0.0f), glm::vec2(0.5f, 1.0f)) == glm::vec2(0.25f, 0.0f));

  using shader::dst_surface_mix;
  surface a = shader::dst_surface_zero(), b = a;
  a.diffuse = glm::vec3(0.2f);
  b.diffuse = glm::vec3(0.6f);
  a.normal = glm::vec3(1, 0, 0);
  b.normal = glm::vec3(0, 1, 0);
  a.depth = 0.5f;
  b.depth = 0.7f;
  // A gradient comes back where the pixel lies on it; the normal stays a unit vector.
  const surface m = dst_surface_mix(a, b, 0.25f);
  CHECK(m.diffuse.x == Approx(0.3f));
  CHECK(m.depth == Approx(0.55f));
  CHECK(glm::length(m.normal) == Approx(1.0f));
  CHECK(m.normal.x > m.normal.y);
  CHECK(dst_surface_mix(a, b, 0.0f).diffuse == a.diffuse);
  CHECK(dst_surface_mix(a, b, 1.0f).normal == b.normal);
  light_sample la = shader::dst_light_sample_zero(), lb = la;
  lb.light = glm::vec3(1.0f);
  lb.specular = glm::vec3(0.5f);
  const light_sample lm = shader::dst_light_mix(la, lb, 0.5f);
  CHECK(lm.light == glm::vec3(0.5f));
  CHECK(lm.specular == glm::vec3(0.25f));
}

TEST_CASE("a history colour is held near this frame's samples on either side: a gradient passes, a sliver does not", "[interlace][temporal]") {
  using shader::dst_history_box;
  const glm::vec3 a(0.2f, 0.5f, 0.0f), b(0.4f, 0.5f, 1.0f);
  // Within the samples' range, and within that range again beyond it: unchanged.
  CHECK(dst_history_box(glm::vec3(0.3f, 0.5f, 0.5f), a, b) == glm::vec3(0.3f, 0.5f, 0.5f));
  CHECK(dst_history_box(glm::vec3(0.6f, 0.52f, 0.0f), a, b) == glm::vec3(0.6f, 0.52f, 0.0f));
  // A colour neither sample shows is held to the range widened by itself and 0.05.
  const glm::vec3 held = dst_history_box(glm::vec3(1.0f, 0.0f, 3.0f), a, b);
  CHECK(held.x == Approx(0.65f));
  CHECK(held.y == Approx(0.45f));
  CHECK(held.z == Approx(2.05f));
  // A NaN bound holds nothing; a NaN colour comes back as the bounds' midpoint.
  const float nan = std::nanf("");
  CHECK(dst_history_box(glm::vec3(0.9f), glm::vec3(nan, 0.0f, 0.0f), glm::vec3(0.1f)).x == 0.9f);
  const glm::vec3 mid = dst_history_box(glm::vec3(nan), a, b);
  CHECK(mid.x == Approx(0.3f));
  CHECK(mid.z == Approx(0.5f));
}

// S2's light bases with the normalisation S2 left open (issue 10): a light along an axis is Lambert
// exactly; for every light direction, the light a surface receives averaged over its normal equals
// Lambert's average; without the normalisation it does not; projections add.
#include <catch2/catch.hpp>

#include <random>

#include <dstrans/light_basis.hpp>
#include <dstrans/light_volume.hpp>

using namespace dstrans;

namespace {

glm::vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<float> g;
  return glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
}

// What a surface of normal n reads when one white light from l is stored in basis b.
float through(const basis& b, glm::vec3 n, glm::vec3 l) {
  std::vector<glm::vec3> values;
  for (float w : b.project(l)) values.push_back(glm::vec3(w));
  return b.evaluate(n, values).x;
}

}  // namespace

TEST_CASE("a light along an axis of the six- or four-axis set is Lambert exactly", "[light_basis]") {
  std::mt19937 rng(10);
  for (const basis& b : {six_axes(), four_axes()})
    for (const glm::vec3& a : b.axes) {
      CHECK(b.norm(a) == Approx(1.0f));
      for (int i = 0; i < 1000; ++i) {
        const glm::vec3 n = random_unit(rng);
        CHECK(through(b, n, a) == Approx(std::max(0.0f, glm::dot(n, a))).margin(1e-6));
      }
    }
}

TEST_CASE("opposite pairs: each axis with its opposite, and a normal faces at most one of a pair", "[light_basis]") {
  using P = std::vector<std::pair<int, int>>;
  CHECK(opposite_pairs(six_axes()) == P{{0, 1}, {2, 3}, {4, 5}});
  CHECK(opposite_pairs(four_axes()).empty());  // a tetrahedron's axes have no opposites
  basis fourteen = six_axes();
  for (int i = 0; i < 8; ++i) fourteen.axes.push_back(glm::normalize(glm::vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1)));
  const P pairs = opposite_pairs(fourteen);
  CHECK(pairs == P{{0, 1}, {2, 3}, {4, 5}, {6, 13}, {7, 12}, {8, 11}, {9, 10}});
  // One fetch a pair reads what the sum over every axis reads.
  std::mt19937 rng(3);
  std::vector<glm::vec3> values;
  for (std::size_t a = 0; a < fourteen.axes.size(); ++a) values.push_back(random_unit(rng) + glm::vec3(1.0f));
  for (int i = 0; i < 1000; ++i) {
    const glm::vec3 n = random_unit(rng);
    glm::vec3 by_pairs(0.0f);
    for (const auto& [a, b] : pairs) {
      const float d = glm::dot(n, fourteen.axes[std::size_t(a)]);
      by_pairs += std::abs(d) * values[std::size_t(d >= 0.0f ? a : b)];
    }
    const glm::vec3 all = fourteen.evaluate(n, values);
    for (int c = 0; c < 3; ++c) CHECK(by_pairs[c] == Approx(all[c]).margin(1e-5));
  }
  basis odd = six_axes();
  odd.axes.pop_back();  // -Z gone: +Z has no opposite
  CHECK(opposite_pairs(odd).empty());
  CHECK(opposite_pairs(basis{}).empty());
}

TEST_CASE("for every light direction the average over normals is Lambert's 1/4, for any set of axes", "[light_basis]") {
  std::mt19937 rng(11);
  basis user;  // a set of seven axes of no particular symmetry that spans every direction
  for (glm::vec3 a : {glm::vec3(1, 0.2f, 0), glm::vec3(-0.3f, 1, 0.1f), glm::vec3(0, -0.5f, 1), glm::vec3(-1, -1, -1),
                      glm::vec3(0.4f, -1, 0.3f), glm::vec3(-1, 0.5f, 0.8f), glm::vec3(0.7f, 0.6f, -1)})
    user.axes.push_back(glm::normalize(a));
  const int normals = 200000;
  std::vector<glm::vec3> ns;
  for (int i = 0; i < normals; ++i) ns.push_back(random_unit(rng));
  for (const basis& b : {six_axes(), four_axes(), user})
    for (glm::vec3 l : {glm::vec3(1, 0, 0), glm::normalize(glm::vec3(1, 1, 1)), glm::normalize(glm::vec3(0.3f, -0.8f, 0.5f))}) {
      double lambert = 0.0, stored = 0.0, unnormalised = 0.0;
      for (const glm::vec3& n : ns) {
        lambert += std::max(0.0f, glm::dot(n, l));
        stored += through(b, n, l);
        unnormalised += through(b, n, l) * b.norm(l);
      }
      INFO(b.axes.size() << " axes, light " << l.x << " " << l.y << " " << l.z);
      CHECK(lambert / normals == Approx(0.25).epsilon(0.01));
      CHECK(stored / normals == Approx(lambert / normals).epsilon(0.01));
      if (b.axes.size() == 6 && l.y > 0.5f) CHECK(unnormalised / normals == Approx(std::sqrt(3.0) / 4.0).epsilon(0.01));
    }
}

TEST_CASE("projections add: two lights stored together read as the sum of each", "[light_basis]") {
  const basis b = six_axes();
  const glm::vec3 l1 = glm::normalize(glm::vec3(1, 2, -0.5f)), l2 = glm::normalize(glm::vec3(-1, 0.3f, 0.2f));
  const glm::vec3 c1(1.0f, 0.5f, 0.2f), c2(0.1f, 0.2f, 0.9f);
  std::vector<glm::vec3> both(6, glm::vec3(0.0f)), one(6, glm::vec3(0.0f)), two(6, glm::vec3(0.0f));
  const auto w1 = b.project(l1), w2 = b.project(l2);
  for (int i = 0; i < 6; ++i) {
    both[std::size_t(i)] = c1 * w1[std::size_t(i)] + c2 * w2[std::size_t(i)];
    one[std::size_t(i)] = c1 * w1[std::size_t(i)];
    two[std::size_t(i)] = c2 * w2[std::size_t(i)];
  }
  const glm::vec3 n = glm::normalize(glm::vec3(0.2f, 0.9f, -0.3f));
  CHECK(glm::length(b.evaluate(n, both) - b.evaluate(n, one) - b.evaluate(n, two)) < 1e-6f);
  basis half;  // axes on one side only: a light from the other side is lost, not divided by zero
  half.axes = {glm::vec3(1, 0, 0)};
  CHECK(half.project(glm::vec3(-1, 0, 0))[0] == 0.0f);
}

TEST_CASE("a baked volume is linear in its lights and samples its cells at their centres", "[light_volume]") {
  const volume_grid g = fit_grid({0.0f, 0.0f, 0.0f}, {2.0f, 1.0f, 3.0f}, {4, 2, 6});
  CHECK(glm::vec3(g.scale) == glm::vec3(0.5f));
  volume_light sun, lamp;
  sun.direction_range = glm::vec4(0.0f, -1.0f, 0.0f, 0.0f);  // straight down: along -Y, an axis of both sets
  lamp.position_kind = glm::vec4(1.0f, 2.0f, 1.0f, 1.0f);
  lamp.direction_range.w = 5.0f;
  for (const basis& b : {six_axes(), four_axes()}) {
    const volume_atlas a = pack_volumes({g}, int(b.axes.size()));
    const auto both = bake_light_volume(a, b, {sun, lamp}), one = bake_light_volume(a, b, {sun}), two = bake_light_volume(a, b, {lamp});
    for (std::size_t i = 0; i < both.size(); ++i) CHECK(glm::length(both[i] - one[i] - two[i]) < 1e-5f);
  }
  // The sun comes from +Y: all of it on the +Y axis of the six-axis set, in every cell.
  const volume_atlas six = pack_volumes({g}, 6);
  const auto cells = bake_light_volume(six, six_axes(), {sun});
  for (int z = 0; z < g.dims.z; ++z)
    for (int y = 0; y < g.dims.y; ++y)
      for (int x = 0; x < g.dims.x; ++x)
        for (int a = 0; a < 6; ++a) CHECK(cells[atlas_texel(six, 0, {x, y, z}, a)].x == (a == 2 ? 1.0f : 0.0f));
  // A point light at a cell's centre has no direction there; the cell next to it is lit from that side.
  volume_light at_centre;
  at_centre.position_kind = glm::vec4(0.25f, 0.25f, 0.25f, 1.0f);  // the centre of cell (0, 0, 0)
  at_centre.direction_range.w = 5.0f;
  const auto near = bake_light_volume(six, six_axes(), {at_centre});
  for (int a = 0; a < 6; ++a) CHECK(near[atlas_texel(six, 0, {0, 0, 0}, a)] == glm::vec4(0.0f));
  CHECK(near[atlas_texel(six, 0, {1, 0, 0}, 1)].x > 0.0f);  // cell (1, 0, 0): the light is towards -X
}

TEST_CASE("packed regions of unequal sizes read back each cell and axis where a particle reads it", "[light_volume]") {
  const std::vector<volume_grid> grids{fit_grid({0, 0, 0}, {1, 2, 1}, {5, 9, 4}), fit_grid({-3, 1, 2}, {-1, 2, 5}, {8, 3, 11}),
                                       fit_grid({2, -1, -1}, {2.5f, 0, 0}, {2, 6, 1})};
  const int axes = 3;
  const volume_atlas atlas = pack_volumes(grids, axes);
  CHECK(atlas.size == glm::ivec3(15, 9 * axes, 11));
  CHECK(atlas.slab == 9);
  // Each texel holds a code naming its region, cell and axis; read it back at the cell's centre.
  auto code = [](std::size_t r, int x, int y, int z, int a) { return int(r * 100000 + a * 10000 + (z * 100 + y) * 10 + x); };
  std::vector<int> texels(std::size_t(atlas.size.x * atlas.size.y * atlas.size.z), -1);
  for (std::size_t r = 0; r < grids.size(); ++r)
    for (int a = 0; a < axes; ++a)
      for (int z = 0; z < grids[r].dims.z; ++z)
        for (int y = 0; y < grids[r].dims.y; ++y)
          for (int x = 0; x < grids[r].dims.x; ++x) {
            int& t = texels[atlas_texel(atlas, r, {x, y, z}, a)];
            CHECK(t == -1);  // no two cells share a texel
            t = code(r, x, y, z, a);
          }
  std::size_t wrong = 0;
  for (std::size_t r = 0; r < grids.size(); ++r) {
    const volume_grid& g = grids[r];
    for (int a = 0; a < axes; ++a) {
      const glm::vec3 offset = glm::vec3(atlas.offsets[r]) + glm::vec3(0.0f, float(a * atlas.slab), 0.0f);
      for (int z = 0; z < g.dims.z; ++z)
        for (int y = 0; y < g.dims.y; ++y)
          for (int x = 0; x < g.dims.x; ++x) {
            const glm::vec3 centre = glm::vec3(g.origin) + (glm::vec3(x, y, z) + 0.5f) * glm::vec3(g.scale);
            const glm::vec3 uvw = shader::dst_volume_texcoord(centre, glm::vec3(g.origin), glm::vec3(g.scale), offset,
                                                              glm::vec3(g.dims), glm::vec3(atlas.size));
            const glm::ivec3 t = glm::ivec3(glm::floor(uvw * glm::vec3(atlas.size)));
            wrong += texels[std::size_t((t.z * atlas.size.y + t.y) * atlas.size.x + t.x)] != code(r, x, y, z, a);
            // Far outside its region a particle still reads its own region and axis, never a neighbour.
            const glm::vec3 far = shader::dst_volume_texcoord(centre + glm::vec3(100.0f), glm::vec3(g.origin), glm::vec3(g.scale),
                                                              offset, glm::vec3(g.dims), glm::vec3(atlas.size));
            const glm::vec3 texel = far * glm::vec3(atlas.size);
            for (int k = 0; k < 3; ++k)
              wrong += texel[k] < offset[k] + 0.5f - 1e-3f || texel[k] > offset[k] + float(g.dims[k]) - 0.5f + 1e-3f;
          }
    }
  }
  CHECK(wrong == 0u);
}

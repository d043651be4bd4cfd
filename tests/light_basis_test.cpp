// S2's light bases with the normalisation S2 left open: a light along an axis is Lambert
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
  for (const volume_model& m : {on_axes(six_axes()), on_axes(four_axes()), light_moments()}) {
    const volume_atlas a = pack_volumes({g}, m.texels());
    const auto both = bake_light_volume(a, m, {sun, lamp}), one = bake_light_volume(a, m, {sun}), two = bake_light_volume(a, m, {lamp});
    for (std::size_t i = 0; i < both.size(); ++i) CHECK(glm::length(both[i] - one[i] - two[i]) < 1e-5f);
    // Every value within the range the lights bound it by.
    const float range = volume_range(g, {sun, lamp});
    for (const glm::vec4& t : both) CHECK(glm::all(glm::lessThanEqual(t, glm::vec4(range * (1.0f + 1e-6f)))));
  }
  CHECK(on_axes(six_axes()).bytes_per_cell() == 20);  // S2's five RGBA8 texels
  CHECK(on_axes(four_axes()).texels() == 3);
  CHECK(light_moments().texels() == 3);
  // The sun comes from +Y: all of it on the +Y axis of the six-axis set (values 6 to 8), in every cell.
  const volume_model six = on_axes(six_axes());
  const volume_atlas atlas = pack_volumes({g}, six.texels());
  const auto cells = bake_light_volume(atlas, six, {sun});
  for (int z = 0; z < g.dims.z; ++z)
    for (int y = 0; y < g.dims.y; ++y)
      for (int x = 0; x < g.dims.x; ++x)
        for (int i = 0; i < 18; ++i) CHECK(cells[atlas_texel(atlas, 0, {x, y, z}, i / 4)][i % 4] == (i >= 6 && i < 9 ? 1.0f : 0.0f));
  // A point light at a cell's centre has no direction there; the cell next to it is lit from that side.
  volume_light at_centre;
  at_centre.position_kind = glm::vec4(0.25f, 0.25f, 0.25f, 1.0f);  // the centre of cell (0, 0, 0)
  at_centre.direction_range.w = 5.0f;
  for (const volume_model& m : {six, light_moments()}) {
    const volume_atlas am = pack_volumes({g}, m.texels());
    const auto near = bake_light_volume(am, m, {at_centre});
    for (int k = 0; k < m.texels(); ++k) CHECK(near[atlas_texel(am, 0, {0, 0, 0}, k)] == glm::vec4(0.0f));
    glm::vec4 next[5];
    for (int k = 0; k < m.texels(); ++k) next[k] = near[atlas_texel(am, 0, {1, 0, 0}, k)];
    // Cell (1, 0, 0): the light is towards -X.
    CHECK(read_cell_light(m, next, {-1.0f, 0.0f, 0.0f}).x > 0.0f);
    CHECK(read_cell_light(m, next, {-1.0f, 0.0f, 0.0f}).x > 4.0f * read_cell_light(m, next, {1.0f, 0.0f, 0.0f}).x);
  }
}

TEST_CASE("a light's moments read back Lambert's average for every direction, and one light exactly where a surface faces it",
          "[light_volume]") {
  std::mt19937 rng(12);
  const volume_model m = light_moments();
  for (int trial = 0; trial < 20; ++trial) {
    // One to three lights of random colours from random directions, as the bake adds them.
    const int count = 1 + trial % 3;
    glm::vec4 t[3] = {glm::vec4(0.0f), glm::vec4(0.0f), glm::vec4(0.0f)};
    std::vector<std::pair<glm::vec3, glm::vec3>> lights;
    std::uniform_real_distribution<float> u(0.1f, 1.0f);
    for (int i = 0; i < count; ++i) {
      const glm::vec3 l = random_unit(rng), c(u(rng), u(rng), u(rng));
      lights.emplace_back(l, c);
      for (int ch = 0; ch < 3; ++ch) t[ch] += c[ch] * shader::dst_moment_weights(l);
    }
    double lambert = 0.0, read = 0.0;
    const int normals = 20000;
    for (int i = 0; i < normals; ++i) {
      const glm::vec3 n = random_unit(rng);
      for (const auto& [l, c] : lights) lambert += c.x * std::max(0.0f, glm::dot(n, l));
      const float v = read_cell_light(m, t, n).x;
      CHECK(std::isfinite(v));
      CHECK(v >= 0.0f);
      read += v;
    }
    CHECK(read / normals == Approx(lambert / normals).epsilon(0.03));
    if (count == 1) {
      const auto& [l, c] = lights[0];
      CHECK(read_cell_light(m, t, l).x == Approx(c.x).epsilon(1e-4));
      CHECK(read_cell_light(m, t, -l).x == Approx(0.0f).margin(1e-6));
    }
  }
  // Light from all around (opposite lights that cancel their directions) reads the same for every normal.
  glm::vec4 even[3] = {};
  for (glm::vec3 l : {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0)})
    for (int ch = 0; ch < 3; ++ch) even[ch] += shader::dst_moment_weights(l);
  CHECK(read_cell_light(m, even, {0, 1, 0}).x == Approx(0.5f));
  CHECK(read_cell_light(m, even, {1, 0, 0}).x == Approx(0.5f));
  // Edge inputs stay finite: nothing stored, texels that no bake writes (|M1| > M0), a NaN normal.
  const glm::vec4 none[3] = {}, odd[3] = {glm::vec4(1.0f, 0.0f, 0.0f, 0.2f), glm::vec4(0.0f), glm::vec4(0.5f)};
  CHECK(read_cell_light(m, none, {0, 0, 1}) == glm::vec3(0.0f));
  CHECK(std::isfinite(read_cell_light(m, odd, {1, 0, 0}).x));
  CHECK(read_cell_light(m, odd, glm::vec3(NAN)).z == Approx(0.0625f));  // as a normal at right angles to the light reads
  CHECK(shader::dst_moment_weights(glm::vec3(0.0f)) == glm::vec4(0.0f));
  CHECK(shader::dst_moment_weights(glm::vec3(NAN, 0.0f, 1.0f)) == glm::vec4(0.0f));
}

TEST_CASE("a volume's range bounds what its lights can reach in it, and is 0 where none does", "[light_volume]") {
  const volume_grid g = fit_grid({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, {2, 2, 2});
  volume_light far, inside, sun;
  far.position_kind = glm::vec4(10.0f, 0.5f, 0.5f, 1.0f);
  far.direction_range.w = 5.0f;  // ends 4 units short of the box
  CHECK(volume_range(g, {far}) == 0.0f);
  inside.position_kind = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  inside.colour_cos_outer = glm::vec4(2.0f, 0.5f, 1.0f, 0.0f);
  CHECK(volume_range(g, {far, inside}) == 2.0f);  // the brightest channel, at full strength
  sun.position_kind.w = 0.0f;
  sun.colour_cos_outer = glm::vec4(0.3f, 0.3f, 0.3f, 0.0f);
  CHECK(volume_range(g, {inside, sun}) == Approx(2.3f));
  volume_light broken = inside;
  broken.colour_cos_outer.x = NAN;
  CHECK(volume_range(g, {broken, sun}) == Approx(0.3f));
  const volume_bake_block dark = bake_block(pack_volumes({g}, 3), 0, 0.0f);
  CHECK(dark.range == glm::vec4(0.0f));  // nothing to store, no division by zero
}

TEST_CASE("one bake dispatch covers every region's cells, each region's block at its index", "[light_volume]") {
  const std::vector<volume_grid> grids{fit_grid({0, 0, 0}, {1, 1, 1}, {5, 9, 4}), fit_grid({2, 0, 0}, {3, 1, 1}, {8, 3, 11})};
  const volume_atlas a = pack_volumes(grids, 3);
  const glm::ivec3 groups = bake_groups(a);
  CHECK(groups == glm::ivec3(4, 3, 3));  // 13 x 9 x 11 texels of the first slab, rounded up to fours
  for (std::size_t r = 0; r < grids.size(); ++r) {
    const glm::ivec3 last = a.offsets[r] + glm::ivec3(grids[r].dims) - 1;
    CHECK(glm::all(glm::lessThan(last, 4 * groups)));
  }
  const std::vector<volume_bake_block> blocks = bake_blocks(a, {2.0f, 0.5f});
  REQUIRE(blocks.size() == 2u);
  CHECK(blocks[1].offset_slab == glm::ivec4(5, 0, 0, 9));
  CHECK(blocks[1].grid.dims == grids[1].dims);
  CHECK(blocks[0].atlas_size == glm::ivec4(13, 27, 11, 0));
  CHECK(blocks[1].range == glm::vec4(0.5f, 2.0f, 0.0f, 0.0f));
  CHECK(bake_blocks(a, {2.0f})[1].range == glm::vec4(0.0f));  // a region without a range stores nothing
  CHECK(bake_groups(pack_volumes({}, 3)) == glm::ivec3(0));     // no region, nothing dispatched
}

TEST_CASE("packed regions of unequal sizes read back each cell and axis where a particle reads it", "[light_volume]") {
  const std::vector<volume_grid> grids{fit_grid({0, 0, 0}, {1, 2, 1}, {5, 9, 4}), fit_grid({-3, 1, 2}, {-1, 2, 5}, {8, 3, 11}),
                                       fit_grid({2, -1, -1}, {2.5f, 0, 0}, {2, 6, 1})};
  const int axes = 3;  // texels a cell
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

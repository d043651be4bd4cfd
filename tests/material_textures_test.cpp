// Textured materials without a GPU: what a material samples, the texture coordinates flatten gives, the
// material block's texture fields, and the one array every texture is resampled into with its mip levels.
#include <catch2/catch.hpp>

#include <dstrans/frame/plan.hpp>
#include <dstrans/material_textures.hpp>

#include "effect_scenes.hpp"

using namespace dstrans;

namespace {

glm::u8vec4 texel_of(const texture_array& a, int level, int layer, int x, int y) {
  const glm::ivec2 size = a.level_size(level);
  const std::uint8_t* p = &a.levels[std::size_t(level)][((std::size_t(layer) * std::size_t(size.y) + std::size_t(y)) * std::size_t(size.x) + std::size_t(x)) * 4u];
  return {p[0], p[1], p[2], p[3]};
}

}  // namespace

TEST_CASE("a material samples a texture or tests alpha; an alpha-tested one is not glass", "[textures]") {
  material m;
  CHECK_FALSE(m.textured());
  m.texture = 0;
  CHECK(m.textured());
  m = material{};
  m.alpha = 0.4f;
  CHECK(m.transparent());
  m.alpha_cutoff = 0.5f;
  CHECK(m.textured());
  CHECK_FALSE(m.transparent());
  m.hair = true;
  CHECK_FALSE(m.textured());
  texture t = testing::chequer(2, 1, {0, 0, 0, 255}, {255, 255, 255, 255});
  CHECK(t.valid());
  t.rgba.pop_back();
  CHECK_FALSE(t.valid());
  CHECK_FALSE(texture{}.valid());
}

TEST_CASE("flatten gives texture coordinates where some shape has them, (0, 0) for the others", "[textures]") {
  scene s;
  s.materials = {material{}};
  s.objects.push_back({shape_pane({1.0f, 1.0f}), glm::mat4(1.0f), 0});
  CHECK_FALSE(has_texture_coordinates(s));
  CHECK(flatten(s).uvs.empty());
  s.objects.push_back(s.objects[0]);
  for (std::size_t i = 0; i < s.objects[1].geometry.positions.size(); ++i) s.objects[1].geometry.uvs.emplace_back(float(i), 0.5f);
  CHECK(has_texture_coordinates(s));
  const scene_mesh m = flatten(s);
  REQUIRE(m.uvs.size() == m.positions.size());
  const std::size_t n = s.objects[0].geometry.positions.size();
  for (std::size_t i = 0; i < n; ++i) {
    CHECK(m.uvs[i] == glm::vec2(0.0f));
    CHECK(m.uvs[n + i] == glm::vec2(float(i), 0.5f));
  }
}

TEST_CASE("a material's block says its layer, cutoff, whether texels set its alpha, and its wrap modes", "[textures]") {
  scene s;
  s.textures = {testing::chequer(2, 2, {255, 0, 0, 255}, {0, 0, 255, 128}), texture{}};
  s.textures[0].wrap_s = wrap::clamp;
  s.textures[0].wrap_t = wrap::mirror;
  material plain, glass, tested, missing, invalid;
  glass.texture = 0;
  glass.alpha = 0.5f;
  tested.texture = 0;
  tested.alpha_cutoff = 0.25f;
  missing.texture = 7;    // no such texture: samples nothing
  invalid.texture = 1;    // an invalid texture: its layer is white
  s.materials = {plain, glass, tested, missing, invalid};
  const std::vector<render::material_block> b = render::material_blocks(s);
  REQUIRE(b.size() == 5);
  CHECK(b[0].texture == glm::vec4(-1.0f, 0.0f, 0.0f, 0.0f));
  CHECK(b[1].texture == glm::vec4(0.0f, 0.0f, 1.0f, 1.0f + 3.0f * 2.0f));
  CHECK(b[2].texture == glm::vec4(0.0f, 0.25f, 1.0f, 7.0f));
  CHECK(b[3].texture == glm::vec4(-1.0f, 0.0f, 0.0f, 0.0f));
  CHECK(b[4].texture.x == 1.0f);
  s.materials[0].alpha_cutoff = std::nanf("");  // not above 0: no test
  CHECK(render::material_blocks(s)[0].texture.y == 0.0f);
}

TEST_CASE("a scene's materials fit a device's texel buffers at three texels each, or are refused saying so", "[textures]") {
  scene s;
  s.materials.resize(5);
  CHECK(render::materials_fit(s, 15));
  CHECK(render::materials_fit(s, 14).error() == "5 materials need 15 texels of a texel buffer; this device's largest holds 14");
  CHECK(render::materials_fit(scene{}, 0));
}

TEST_CASE("the texture array: one size for every layer, exact where a texture has it, averaged where shrunk", "[textures]") {
  scene s;
  s.textures = {testing::chequer(4, 2, {255, 0, 0, 255}, {0, 0, 255, 0}),   // 8 x 8
                testing::chequer(2, 1, {10, 20, 30, 40}, {50, 60, 70, 80}),  // 2 x 2, magnified
                texture{}};                                                  // invalid: white
  const texture_array a = texture_array_of(s);
  CHECK(a.width == 8);
  CHECK(a.height == 8);
  CHECK(a.layers == 3);
  REQUIRE(a.levels.size() == 4);  // 8, 4, 2, 1
  CHECK(a.level_size(3) == glm::ivec2(1));
  CHECK(a.level_size(9) == glm::ivec2(1));
  for (int l = 0; l < 4; ++l) CHECK(a.levels[std::size_t(l)].size() == std::size_t(a.level_size(l).x * a.level_size(l).y) * 4u * 3u);
  CHECK(texture_array_bytes(s) == (64u + 16u + 4u + 1u) * 4u * 3u);
  CHECK(texture_array_shape(s).levels.empty());
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const glm::u8vec4 want = ((x / 2) + (y / 2)) % 2 ? glm::u8vec4(0, 0, 255, 0) : glm::u8vec4(255, 0, 0, 255);
      CHECK(texel_of(a, 0, 0, x, y) == want);
      CHECK(texel_of(a, 0, 2, x, y) == glm::u8vec4(255));
    }
  // Level 1 of the chequer of 2-texel squares: each texel is one square.
  CHECK(texel_of(a, 1, 0, 0, 0) == glm::u8vec4(255, 0, 0, 255));
  CHECK(texel_of(a, 1, 0, 1, 0) == glm::u8vec4(0, 0, 255, 0));
  // Level 3: the mean of everything.
  CHECK(texel_of(a, 3, 0, 0, 0) == glm::u8vec4(128, 0, 128, 128));
  // The magnified 2 x 2: its corners keep their texels, bilinear between.
  CHECK(texel_of(a, 0, 1, 0, 0) == glm::u8vec4(10, 20, 30, 40));
  CHECK(texel_of(a, 0, 1, 7, 0) == glm::u8vec4(50, 60, 70, 80));
  const glm::u8vec4 middle = texel_of(a, 0, 1, 3, 0);
  CHECK(middle.r > 10);
  CHECK(middle.r < 50);
  // Shrunk to at most 4 a side: each texel averages the 2 x 2 it covers, whole squares here.
  const texture_array small = texture_array_of(s, 4);
  CHECK(small.width == 4);
  CHECK(texel_of(small, 0, 0, 0, 0) == glm::u8vec4(255, 0, 0, 255));
  CHECK(texel_of(small, 0, 0, 1, 0) == glm::u8vec4(0, 0, 255, 0));
  // Without textures: one white texel, for a frame that forces the effect.
  const texture_array none = texture_array_of(scene{});
  CHECK(none.layers == 1);
  CHECK(none.levels.size() == 1);
  CHECK(texel_of(none, 0, 0, 0, 0) == glm::u8vec4(255));
}

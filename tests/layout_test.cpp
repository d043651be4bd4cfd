// Layout facts (Tables 3.1-3.3), CPU pack/unpack and write/read, and the layout description.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include <dstrans/gbuffer.hpp>

using namespace dstrans;

namespace {
surface sample_surface() {
  surface s = shader::dst_surface_zero();
  s.diffuse = {1.0f, 0.0f, 0.2f};
  s.alpha = 0.6f;
  s.normal = glm::normalize(glm::vec3(0.3f, -0.5f, 0.81f));
  s.spec_intensity = 0.75f;
  s.spec_power = 32.0f;
  s.depth = 0.123456789f;
  return s;
}

// A float-heavy layout that exercises the non-UNORM paths.
using float_layout = layout<surface, target<format::rgba16f, field::normal, field::alpha>,
                            target<format::rgba32f, field::diffuse, field::depth>,
                            target<format::rg16f, field::spec_intensity, field::spec_power>>;
}  // namespace

static_assert(thesis_gbuffer::target_count == 4 && thesis_gbuffer::bytes_per_pixel == 16);
static_assert(thesis_light_buffer::target_count == 1 && thesis_light_buffer::bytes_per_pixel == 4);
static_assert(thesis_shadow_map::target_count == 2 && thesis_shadow_map::bytes_per_pixel == 8);
static_assert(thesis_gbuffer::stores<field::normal>() && !thesis_shadow_map::stores<field::normal>());
static_assert(requires_fields<thesis_shadow_map, field::depth, field::diffuse, field::alpha>());
static_assert(float_layout::bytes_per_pixel == 8 + 16 + 4);

TEST_CASE("the thesis layouts are Tables 3.1, 3.2 and 3.3", "[layout]") {
  const auto g = describe<thesis_gbuffer>();
  REQUIRE(g.size() == 4);
  CHECK(g[0].fmt == format::rgba8);
  CHECK(g[0].channels == std::vector<std::string>{"diffuse.r", "diffuse.g", "diffuse.b", "alpha"});
  CHECK(g[1].fmt == format::rgb10a2);
  CHECK(g[1].channels == std::vector<std::string>{"normal.x", "normal.y", "normal.z", "unused"});
  CHECK(g[2].fmt == format::rgba8);
  CHECK(g[2].channels == std::vector<std::string>{"spec_intensity", "spec_power", "unused", "unused"});
  CHECK(g[3].fmt == format::r32f);
  CHECK(g[3].channels == std::vector<std::string>{"depth"});

  const auto l = describe<thesis_light_buffer>();
  REQUIRE(l.size() == 1);
  CHECK(l[0].fmt == format::rgba8);
  CHECK(l[0].channels == std::vector<std::string>{"light.r", "light.g", "light.b", "specular"});

  const auto s = describe<thesis_shadow_map>();
  REQUIRE(s.size() == 2);
  CHECK(s[0].fmt == format::r32f);
  CHECK(s[1].channels == std::vector<std::string>{"diffuse.r", "diffuse.g", "diffuse.b", "alpha"});
}

TEST_CASE("pack applies each field's UNORM codec and places channels in order", "[layout]") {
  const surface s = sample_surface();
  const auto v = pack<thesis_gbuffer>(s);
  CHECK(v[0] == glm::vec4(s.diffuse, s.alpha));
  CHECK(v[1] == glm::vec4(shader::dst_encode_normal(s.normal), 0.0f));
  CHECK(v[2] == glm::vec4(0.75f, shader::dst_encode_spec_power(32.0f), 0.0f, 0.0f));
  CHECK(v[3] == glm::vec4(s.depth, 0.0f, 0.0f, 0.0f));
  // Float targets store fields as they are.
  const auto f = pack<float_layout>(s);
  CHECK(f[0] == glm::vec4(s.normal, s.alpha));
  CHECK(f[2] == glm::vec4(0.75f, 32.0f, 0.0f, 0.0f));
  const surface back = unpack<float_layout>(f);
  CHECK(back.normal == s.normal);
  CHECK(back.spec_power == 32.0f);
  CHECK(back.depth == s.depth);
}

TEST_CASE("write gives the GPU's bytes and read inverts it within quantisation", "[layout]") {
  const surface s = sample_surface();
  const auto t = write<thesis_gbuffer>(s);
  CHECK(t[0][0] == 255);
  CHECK(t[0][1] == 0);
  CHECK(t[0][2] == 51);
  CHECK(t[0][3] == 153);
  CHECK(t[2][1] == 32);  // every integer power survives 8 bits
  const surface r = read<thesis_gbuffer>(t);
  CHECK(r.alpha == 153.0f / 255.0f);
  CHECK(r.spec_power == Approx(32.0f).margin(1e-4));
  CHECK(r.depth == s.depth);  // R32F is exact
  for (int i = 0; i < 3; ++i) CHECK(r.normal[i] == Approx(s.normal[i]).margin(1.0 / 1023.0));
  // read(write(read(x))) == read(x): quantised values are fixed points.
  const auto t2 = write<thesis_gbuffer>(r);
  CHECK(t2 == t);
}

TEST_CASE("fields a layout does not store read back as zero", "[layout]") {
  const surface r = read<thesis_shadow_map>(write<thesis_shadow_map>(sample_surface()));
  CHECK(r.normal == glm::vec3(0.0f));
  CHECK(r.spec_power == 0.0f);
  CHECK(r.alpha == 153.0f / 255.0f);

  light_sample ls = shader::dst_light_sample_zero();
  ls.light = {2.0f, 0.5f, -1.0f};  // RGBA8 saturates, as the thesis's light buffer does
  ls.specular = {0.5f, 0.25f, 0.0f};  // Table 3.2 keeps the mean, read back as grey
  const light_sample lr = read<thesis_light_buffer>(write<thesis_light_buffer>(ls));
  CHECK(lr.light == glm::vec3(1.0f, 128.0f / 255.0f, 0.0f));
  CHECK(lr.specular == glm::vec3(64.0f / 255.0f));
}

static_assert(rgb_light_buffer::bytes_per_pixel == 8 && rgb_light_buffer::target_count == 2);

TEST_CASE("the RGB-specular light buffer keeps the specular's colour through RGBA8", "[layout]") {
  light_sample ls = shader::dst_light_sample_zero();
  ls.light = {0.5f, 0.25f, 1.0f};
  ls.specular = {1.0f, 0.5f, 0.0f};
  const light_sample r = read<rgb_light_buffer>(write<rgb_light_buffer>(ls));
  CHECK(r.light == glm::vec3(128.0f / 255.0f, 64.0f / 255.0f, 1.0f));
  CHECK(r.specular == glm::vec3(1.0f, 128.0f / 255.0f, 0.0f));
  const auto d = describe<rgb_light_buffer>();
  REQUIRE(d.size() == 2);
  CHECK(d[1].channels == std::vector<std::string>{"specular.r", "specular.g", "specular.b", "unused"});
}

// The compact layout holds Table 3.1's information in half the bytes, with the light buffer 12.
static_assert(compact_gbuffer::bytes_per_pixel == 8 && compact_gbuffer::target_count == 2);
static_assert(compact_gbuffer::bytes_per_pixel + thesis_light_buffer::bytes_per_pixel <= 12);

TEST_CASE("the compact layout keeps every field, its normal within 1 degree, through RGBA8", "[layout][compact]") {
  std::uint32_t state = 12345u;
  auto next = [&] {
    state = state * 747796405u + 2891336453u;
    return float((state >> 8) & 0xffffffu) / float(0xffffff) * 2.0f - 1.0f;
  };
  float worst = 0.0f;
  for (int i = 0; i < 200000; ++i) {
    glm::vec3 n(next(), next(), next());
    if (glm::length(n) < 1e-3f) continue;
    surface s = shader::dst_surface_zero();
    s.normal = glm::normalize(n);
    const surface back = read<compact_gbuffer>(write<compact_gbuffer>(s));
    worst = std::max(worst, glm::degrees(std::acos(std::min(1.0f, glm::dot(s.normal, back.normal)))));
  }
  INFO("worst angular error " << worst << " degrees");
  CHECK(worst < 1.0f);  // measured 0.94
  // The axes and the octahedron's folds come back exactly or nearly.
  for (glm::vec3 n : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(1, 0, 0), glm::vec3(0, -1, 0)}) {
    surface s = shader::dst_surface_zero();
    s.normal = n;
    CHECK(glm::dot(read<compact_gbuffer>(write<compact_gbuffer>(s)).normal, n) > 0.9999f);
  }
  // The other fields as Table 3.1 keeps them.
  surface s = shader::dst_surface_zero();
  s.diffuse = {0.2f, 0.4f, 0.6f};
  s.alpha = 0.4f;
  s.normal = {0.0f, 1.0f, 0.0f};
  s.spec_intensity = 0.8f;
  s.spec_power = 64.0f;
  const surface a = read<compact_gbuffer>(write<compact_gbuffer>(s)), b = read<thesis_gbuffer>(write<thesis_gbuffer>(s));
  CHECK(a.diffuse == b.diffuse);
  CHECK(a.alpha == b.alpha);
  CHECK(a.spec_intensity == b.spec_intensity);
  CHECK(a.spec_power == b.spec_power);
  CHECK(a.depth == 0.0f);  // not stored: read from the depth attachment
}

TEST_CASE("an alpha below 1 stays transparent and 1 stays opaque through every layout that stores alpha", "[layout][alpha]") {
  const float alphas[] = {1.0f - 0x1p-24f, 0.999f, 254.5f / 255.0f, 1.0f / 255.0f, 0.5f / 255.0f, 0.0f, 1.0f, 1.5f, NAN};
  for (float a : alphas) {
    surface s = shader::dst_surface_zero();
    s.alpha = a;
    const bool transparent = a < 1.0f;  // NaN is not below 1: opaque
    INFO("alpha " << a);
    CHECK(shader::dst_transparent(read<thesis_gbuffer>(write<thesis_gbuffer>(s)).alpha) == transparent);
    CHECK(shader::dst_transparent(read<compact_gbuffer>(write<compact_gbuffer>(s)).alpha) == transparent);
    CHECK(shader::dst_transparent(read<thesis_shadow_map>(write<thesis_shadow_map>(s)).alpha) == transparent);
    // The RGBA8 code: 255 only for opaque, and transparent ones keep their nearest code up to 254.
    const int code = write<thesis_gbuffer>(s)[0][3];
    CHECK((code == 255) == !transparent);
    if (transparent) CHECK(std::abs(float(code) - std::min(254.0f, a * 255.0f)) <= 0.5f + 1e-4f);
  }
}

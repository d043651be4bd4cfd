// Format conversions against the OpenGL 4.5 / Vulkan rules at their boundaries.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include <dstrans/format.hpp>

using namespace dstrans;

namespace {
float bits_to_float(std::uint32_t x) {
  float f;
  std::memcpy(&f, &x, 4);
  return f;
}
std::uint32_t float_to_bits(float f) {
  std::uint32_t x;
  std::memcpy(&x, &f, 4);
  return x;
}
const float nan_f = std::numeric_limits<float>::quiet_NaN();
const float inf_f = std::numeric_limits<float>::infinity();
}  // namespace

TEST_CASE("format facts match the APIs' tables", "[format]") {
  CHECK(info(format::rgba8).bytes_per_pixel == 4);
  CHECK(info(format::rgb10a2).bytes_per_pixel == 4);
  CHECK(info(format::r32f).bytes_per_pixel == 4);
  CHECK(info(format::r16f).bytes_per_pixel == 2);
  CHECK(info(format::rg16f).bytes_per_pixel == 4);
  CHECK(info(format::rgba16f).bytes_per_pixel == 8);
  CHECK(info(format::rg32f).bytes_per_pixel == 8);
  CHECK(info(format::rgba32f).bytes_per_pixel == 16);
  CHECK(info(format::r8).bytes_per_pixel == 1);
  CHECK(info(format::rg8).bytes_per_pixel == 2);
  for (format f : all_formats) {
    const format_info fi = info(f);
    int bits = 0;
    for (int c = 0; c < fi.channels; ++c) bits += fi.bits[std::size_t(c)];
    CHECK(bits == 8 * fi.bytes_per_pixel);
  }
  CHECK(std::string(info(format::rgb10a2).name) == "RGB10A2");
}

TEST_CASE("UNORM encoding clamps, rounds to nearest and stores NaN as 0", "[format]") {
  for (int bits : {2, 8, 10}) {
    const std::uint32_t top = (1u << bits) - 1u;
    CHECK(unorm_encode(0.0f, bits) == 0u);
    CHECK(unorm_encode(-0.0f, bits) == 0u);
    CHECK(unorm_encode(1.0f, bits) == top);
    CHECK(unorm_encode(-0.25f, bits) == 0u);
    CHECK(unorm_encode(7.0f, bits) == top);
    CHECK(unorm_encode(inf_f, bits) == top);
    CHECK(unorm_encode(-inf_f, bits) == 0u);
    CHECK(unorm_encode(nan_f, bits) == 0u);
    for (std::uint32_t k = 0; k <= top; ++k) {
      // Every code survives a round trip, and values either side of a half quantum round to the nearer code.
      REQUIRE(unorm_encode(unorm_decode(k, bits), bits) == k);
      const float mid = (float(k) + 0.5f) / float(top);
      if (k < top) {
        CHECK(unorm_encode(std::nextafter(mid, 0.0f) - 1e-6f, bits) == k);
        CHECK(unorm_encode(std::nextafter(mid, 1.0f) + 1e-6f, bits) == k + 1);
      }
    }
  }
  // An exact tie (x.5 after the exact multiply) goes to the even code.
  CHECK(unorm_encode(0.5f, 2) == 2u);   // 1.5 -> 2
  CHECK(unorm_encode(0.5f, 10) == 512u);  // 511.5 -> 512
  CHECK(unorm_decode(255u, 8) == 1.0f);
  CHECK(unorm_decode(128u, 8) == 128.0f / 255.0f);
}

TEST_CASE("half floats round to nearest even, overflow to infinity and keep subnormals", "[format]") {
  CHECK(half_encode(0.0f) == 0x0000u);
  CHECK(half_encode(-0.0f) == 0x8000u);
  CHECK(half_encode(1.0f) == 0x3c00u);
  CHECK(half_encode(-2.0f) == 0xc000u);
  CHECK(half_encode(65504.0f) == 0x7bffu);
  CHECK(half_encode(std::nextafter(65520.0f, 0.0f)) == 0x7bffu);
  CHECK(half_encode(65520.0f) == 0x7c00u);  // the tie past the largest half goes to infinity
  CHECK(half_encode(1e10f) == 0x7c00u);
  CHECK(half_encode(inf_f) == 0x7c00u);
  CHECK(half_encode(-inf_f) == 0xfc00u);
  CHECK(half_encode(std::ldexp(1.0f, -14)) == 0x0400u);  // smallest normal
  CHECK(half_encode(std::ldexp(1.0f, -24)) == 0x0001u);  // smallest subnormal
  CHECK(half_encode(std::ldexp(1.0f, -25)) == 0x0000u);  // tie with 0: even
  CHECK(half_encode(std::ldexp(3.0f, -26)) == 0x0001u);
  CHECK(half_encode(1.0f + std::ldexp(1.0f, -11)) == 0x3c00u);        // tie: even mantissa 0
  CHECK(half_encode(1.0f + std::ldexp(3.0f, -11)) == 0x3c02u);        // tie: even mantissa 2
  CHECK(half_encode(std::ldexp(1023.5f, -24)) == 0x0400u);            // subnormal rounding carries into normal
  const std::uint16_t n = half_encode(nan_f);
  CHECK((n & 0x7c00u) == 0x7c00u);
  CHECK((n & 0x03ffu) != 0u);
  CHECK(std::isnan(half_decode(n)));
  CHECK(std::signbit(half_decode(half_encode(-nan_f))));

  // Every half survives a round trip through float.
  for (std::uint32_t h = 0; h < 0x10000u; ++h) {
    const float f = half_decode(std::uint16_t(h));
    if (std::isnan(f)) continue;
    REQUIRE(half_encode(f) == h);
  }
}

#ifdef __FLT16_MAX__
TEST_CASE("half encoding agrees with the compiler's IEEE binary16 conversion", "[format]") {
  std::mt19937 rng(1234);
  for (int i = 0; i < 1000000; ++i) {
    const float f = bits_to_float(rng());
    if (std::isnan(f)) continue;
    const _Float16 ref = static_cast<_Float16>(f);
    std::uint16_t bits;
    std::memcpy(&bits, &ref, 2);
    REQUIRE(half_encode(f) == bits);
  }
}
#endif

TEST_CASE("texels hold the bytes the APIs define", "[format]") {
  texel t = encode(format::rgba8, {1.0f, 0.0f, 0.5f, 0.2f});
  CHECK(t[0] == 255);
  CHECK(t[1] == 0);
  CHECK(t[2] == 128);  // 127.5 -> 128
  CHECK(t[3] == 51);

  // RGB10A2 is one little-endian word, red in the low bits (GL_UNSIGNED_INT_2_10_10_10_REV, VK A2B10G10R10).
  t = encode(format::rgb10a2, {1.0f, 0.0f, 0.0f, 1.0f});
  std::uint32_t word = std::uint32_t(t[0]) | std::uint32_t(t[1]) << 8 | std::uint32_t(t[2]) << 16 | std::uint32_t(t[3]) << 24;
  CHECK(word == 0xc00003ffu);
  t = encode(format::rgb10a2, {0.0f, 1.0f, 1.0f, 0.0f});
  word = std::uint32_t(t[0]) | std::uint32_t(t[1]) << 8 | std::uint32_t(t[2]) << 16 | std::uint32_t(t[3]) << 24;
  CHECK(word == 0x3ffffc00u);

  t = encode(format::rg16f, {1.0f, -2.0f, 9.0f, 9.0f});
  CHECK(t[0] == 0x00);
  CHECK(t[1] == 0x3c);
  CHECK(t[2] == 0x00);
  CHECK(t[3] == 0xc0);
  CHECK(t[4] == 0);

  // 32-bit floats keep every bit, NaN payloads and negative zero included.
  const float payload = bits_to_float(0x7fc01234u);
  t = encode(format::rgba32f, {payload, -0.0f, inf_f, 3.25f});
  const glm::vec4 back = decode(format::rgba32f, t);
  CHECK(float_to_bits(back.x) == 0x7fc01234u);
  CHECK(float_to_bits(back.y) == 0x80000000u);
  CHECK(back.z == inf_f);
  CHECK(back.w == 3.25f);
}

TEST_CASE("decoding fills absent channels with 0, 0, 1", "[format]") {
  for (format f : all_formats) {
    const glm::vec4 v = decode(f, encode(f, {0.25f, 0.5f, 0.75f, 0.0f}));
    const int n = info(f).channels;
    CHECK(v.x == Approx(0.25f).margin(1e-2));
    if (n < 2) CHECK(v.y == 0.0f);
    if (n < 3) CHECK(v.z == 0.0f);
    if (n < 4) CHECK(v.w == 1.0f);
  }
}

TEST_CASE("quantize is what a shader reads back", "[format]") {
  CHECK(quantize(format::rgba8, {0.5f, 0.0f, 0.0f, 1.0f}).x == 128.0f / 255.0f);
  CHECK(quantize(format::r16f, {0.1f, 0.0f, 0.0f, 0.0f}).x == half_decode(half_encode(0.1f)));
  CHECK(quantize(format::r32f, {0.1f, 0.0f, 0.0f, 0.0f}).x == 0.1f);
  CHECK(quantize(format::rgb10a2, {0.0f, 0.0f, 0.0f, 0.5f}).w == 2.0f / 3.0f);
}

TEST_CASE("permitted accepts either neighbouring code and nothing further", "[format]") {
  // 0.236 * 1023 = 241.52: 241 and 242 are both within the rules; 240 and 243 are not.
  const glm::vec4 v{0.236088976f, 0.0f, 1.0f, 0.5f};
  auto with_red = [&](std::uint32_t red) {
    const std::uint32_t word = red | (1023u << 20) | (2u << 30);
    texel t{};
    for (int i = 0; i < 4; ++i) t[std::size_t(i)] = std::uint8_t(word >> (8 * i));
    return t;
  };
  CHECK(permitted(format::rgb10a2, v, with_red(241)));
  CHECK(permitted(format::rgb10a2, v, with_red(242)));
  CHECK_FALSE(permitted(format::rgb10a2, v, with_red(240)));
  CHECK_FALSE(permitted(format::rgb10a2, v, with_red(243)));
  CHECK(permitted(format::rgb10a2, v, encode(format::rgb10a2, v)));
  // Exact products allow only their integer; NaN must store 0; out of range clamps.
  CHECK_FALSE(permitted(format::rgba8, {1.0f, 0, 0, 0}, encode(format::rgba8, {254.0f / 255.0f, 0, 0, 0})));
  CHECK_FALSE(permitted(format::rgb10a2, {0.0f, 0.5f, 0.25f, 1.0f / 3.0f}, encode(format::rgb10a2, {0.0f, 0.5f, 0.25f, 0.0f})));
  CHECK_FALSE(permitted(format::rgba8, {128.0f / 255.0f, 0, 0, 0}, encode(format::rgba8, {127.0f / 255.0f, 0, 0, 0})));
  CHECK(permitted(format::rgba8, {nan_f, 2.0f, -1.0f, 0.0f}, encode(format::rgba8, {0.0f, 1.0f, 0.0f, 0.0f})));
  CHECK_FALSE(permitted(format::rgba8, {nan_f, 0, 0, 0}, encode(format::rgba8, {1.0f / 255.0f, 0, 0, 0})));

  // Halves: round-to-nearest and round-toward-zero neighbours pass, a half two steps away does not.
  const float x = 0.932557344f;  // between halves 0x3b75 and 0x3b76
  auto half_texel = [](std::uint16_t h) {
    texel t{};
    t[0] = std::uint8_t(h);
    t[1] = std::uint8_t(h >> 8);
    return t;
  };
  CHECK(permitted(format::r16f, {x, 0, 0, 0}, half_texel(0x3b76)));
  CHECK(permitted(format::r16f, {x, 0, 0, 0}, half_texel(0x3b75)));
  CHECK_FALSE(permitted(format::r16f, {x, 0, 0, 0}, half_texel(0x3b74)));
  CHECK(permitted(format::r16f, {70000.0f, 0, 0, 0}, half_texel(0x7bff)));  // largest finite
  CHECK(permitted(format::r16f, {70000.0f, 0, 0, 0}, half_texel(0x7c00)));  // or infinity
  CHECK(permitted(format::r16f, {-1e-8f, 0, 0, 0}, half_texel(0x8000)));
  CHECK(permitted(format::r16f, {nan_f, 0, 0, 0}, half_texel(0x7e00)));
  CHECK_FALSE(permitted(format::r16f, {1.0f, 0, 0, 0}, half_texel(0x3c01)));
  // 32-bit floats must be exact, except for a NaN's payload.
  CHECK(permitted(format::r32f, {0.1f, 0, 0, 0}, encode(format::r32f, {0.1f, 0, 0, 0})));
  CHECK_FALSE(permitted(format::r32f, {0.1f, 0, 0, 0}, encode(format::r32f, {std::nextafter(0.1f, 1.0f), 0, 0, 0})));
  CHECK(permitted(format::r32f, {nan_f, 0, 0, 0}, encode(format::r32f, {bits_to_float(0x7fc01234u), 0, 0, 0})));

  // Every value's own encoding is permitted.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> d(-0.5f, 1.5f);
  for (int i = 0; i < 20000; ++i)
    for (format f : all_formats) {
      const glm::vec4 w{d(rng), d(rng), d(rng), d(rng)};
      REQUIRE(permitted(f, w, encode(f, w)));
    }
}

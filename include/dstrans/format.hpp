// Render-target formats and their CPU conversions, bit-exact with what a GPU stores.
//
//   using namespace dstrans;
//   texel t = encode(format::rgb10a2, {0.5f, 1.0f, -3.0f, 0.7f});   // the bytes a GPU writes
//   glm::vec4 v = decode(format::rgb10a2, t);                         // what a shader reads back
//   static_assert(info(format::rgba16f).bytes_per_pixel == 8);
//
// The conversions follow the OpenGL 4.5 (2.3.5) and Vulkan ("Fixed-Point Data Conversions",
// "Floating-Point Format Conversions") rules. Those rules let a GPU store either of two neighbouring
// codes for a value between them; encode() takes the one the specs prefer (the nearest) and
// permitted() says whether bytes a GPU stored are within the rules:
// - UNORM with b bits: the value is clamped to [0, 1] and multiplied by 2^b - 1 exactly; the code is the
//   nearest integer (an exact tie rounds to even), and the rules permit either integer next to the
//   product (exactly it when it is an integer). NaN stores 0, as D3D requires and Mesa does. Reading
//   gives c / (2^b - 1), rounded once to float.
// - 16-bit float: encode() rounds to nearest even, magnitudes from 65520 up become infinity, subnormal
//   halves are kept, NaN stays a quiet NaN with its sign; the rules permit either neighbouring half
//   (Mesa's llvmpipe rounds toward zero), and past the largest finite half either it or infinity.
// - 32-bit float: stored as is; a GPU may change a NaN's payload.
// - Reading a format with fewer than four channels fills G and B with 0 and A with 1.
// Taken literally, the rules even permit code k+1 for the float nearest k/(2^b-1), whose exact product
// lies a hair above k; GPUs (Mesa included) return k, so a G-buffer that is written, read and written
// again keeps its bytes, and dstrans's tests require that bit for bit.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <glm/glm.hpp>

namespace dstrans {

enum class format : std::uint8_t { r8, rg8, rgba8, rgb10a2, r16f, rg16f, rgba16f, r32f, rg32f, rgba32f };

enum class channel_kind : std::uint8_t { unorm, sfloat };

// What the APIs call a format and how it is laid out in memory.
struct format_info {
  const char* name;               // the name the thesis's tables use, e.g. "RGB10A2"
  channel_kind kind;              // how each channel converts
  int channels;                   // stored channels, 1 to 4
  std::array<int, 4> bits;        // bits of each stored channel, 0 past `channels`
  int bytes_per_pixel;            // bytes of one texel in memory
  unsigned gl_internal_format;    // the GLenum for glTexStorage2D (no GL header needed)
  int vk_format;                  // the VkFormat value (no Vulkan header needed)
  const char* glsl_image_format;  // the GLSL image layout qualifier
};

inline constexpr format all_formats[] = {format::r8,      format::rg8,   format::rgba8,   format::rgb10a2,
                                         format::r16f,    format::rg16f, format::rgba16f, format::r32f,
                                         format::rg32f,   format::rgba32f};

// The facts of format `f`.
constexpr format_info info(format f) {
  switch (f) {
    case format::r8: return {"R8", channel_kind::unorm, 1, {8, 0, 0, 0}, 1, 0x8229u, 9, "r8"};
    case format::rg8: return {"RG8", channel_kind::unorm, 2, {8, 8, 0, 0}, 2, 0x822Bu, 16, "rg8"};
    case format::rgba8: return {"RGBA8", channel_kind::unorm, 4, {8, 8, 8, 8}, 4, 0x8058u, 37, "rgba8"};
    case format::rgb10a2: return {"RGB10A2", channel_kind::unorm, 4, {10, 10, 10, 2}, 4, 0x8059u, 64, "rgb10_a2"};
    case format::r16f: return {"R16F", channel_kind::sfloat, 1, {16, 0, 0, 0}, 2, 0x822Du, 76, "r16f"};
    case format::rg16f: return {"RG16F", channel_kind::sfloat, 2, {16, 16, 0, 0}, 4, 0x822Fu, 83, "rg16f"};
    case format::rgba16f: return {"RGBA16F", channel_kind::sfloat, 4, {16, 16, 16, 16}, 8, 0x881Au, 97, "rgba16f"};
    case format::r32f: return {"R32F", channel_kind::sfloat, 1, {32, 0, 0, 0}, 4, 0x822Eu, 100, "r32f"};
    case format::rg32f: return {"RG32F", channel_kind::sfloat, 2, {32, 32, 0, 0}, 8, 0x8230u, 103, "rg32f"};
    case format::rgba32f: return {"RGBA32F", channel_kind::sfloat, 4, {32, 32, 32, 32}, 16, 0x8814u, 109, "rgba32f"};
  }
  return {"?", channel_kind::unorm, 0, {0, 0, 0, 0}, 0, 0u, 0, "?"};
}

// One texel's bytes, as they lie in a mapped image or a glReadPixels buffer; the first
// info(f).bytes_per_pixel bytes are used.
using texel = std::array<std::uint8_t, 16>;

// The UNORM code of `v` with `bits` bits (1 to 16).
inline std::uint32_t unorm_encode(float v, int bits) {
  const double top = double((1u << bits) - 1u);
  if (std::isnan(v)) return 0u;
  const double clamped = v < 0.0f ? 0.0 : (v > 1.0f ? 1.0 : double(v));
  return std::uint32_t(std::nearbyint(clamped * top));  // the product is exact in double
}

// The value a shader reads from UNORM code `c` of `bits` bits.
inline float unorm_decode(std::uint32_t c, int bits) { return float(c) / float((1u << bits) - 1u); }

// The IEEE binary16 bits of `v`, rounded to nearest even.
inline std::uint16_t half_encode(float v) {
  std::uint32_t x;
  std::memcpy(&x, &v, 4);
  const std::uint32_t sign = (x >> 16) & 0x8000u;
  const std::uint32_t mag = x & 0x7fffffffu;
  if (mag > 0x7f800000u) return std::uint16_t(sign | 0x7e00u | ((mag >> 13) & 0x3ffu));  // NaN, quiet
  if (mag >= 0x477ff000u) return std::uint16_t(sign | 0x7c00u);  // >= 65520 (or inf): infinity
  if (mag < 0x38800000u) {                                        // below 2^-14: subnormal half
    float a;
    std::memcpy(&a, &mag, 4);
    return std::uint16_t(sign | std::uint32_t(std::nearbyint(a * 16777216.0f)));  // exact scale by 2^24
  }
  // Rebias the exponent (127 -> 15) and round the 13 dropped mantissa bits to nearest even; a carry
  // out of the mantissa correctly bumps the exponent.
  const std::uint32_t rounded = mag - 0x38000000u + 0xfffu + ((mag >> 13) & 1u);
  return std::uint16_t(sign | (rounded >> 13));
}

// The float that binary16 bits `h` denote (exact: every half is a float).
inline float half_decode(std::uint16_t h) {
  const std::uint32_t sign = std::uint32_t(h & 0x8000u) << 16;
  const std::uint32_t exp = (h >> 10) & 0x1fu;
  const std::uint32_t man = h & 0x3ffu;
  std::uint32_t x;
  if (exp == 0u) {  // zero or subnormal: man * 2^-24, exact in float
    const float v = float(man) * (1.0f / 16777216.0f);
    std::memcpy(&x, &v, 4);
    x |= sign;
  } else if (exp == 31u) {
    x = sign | 0x7f800000u | (man << 13);
  } else {
    x = sign | ((exp + 112u) << 23) | (man << 13);
  }
  float v;
  std::memcpy(&v, &x, 4);
  return v;
}

// The bytes a GPU stores when a shader writes `v` to a target of format `f`.
inline texel encode(format f, glm::vec4 v) {
  const format_info fi = info(f);
  texel t{};
  if (f == format::rgb10a2) {
    const std::uint32_t word = unorm_encode(v.x, 10) | (unorm_encode(v.y, 10) << 10) |
                               (unorm_encode(v.z, 10) << 20) | (unorm_encode(v.w, 2) << 30);
    for (int i = 0; i < 4; ++i) t[i] = std::uint8_t(word >> (8 * i));
    return t;
  }
  for (int c = 0; c < fi.channels; ++c) {
    if (fi.kind == channel_kind::unorm) {
      t[c] = std::uint8_t(unorm_encode(v[c], 8));
    } else if (fi.bits[c] == 16) {
      const std::uint16_t h = half_encode(v[c]);
      t[2 * c] = std::uint8_t(h);
      t[2 * c + 1] = std::uint8_t(h >> 8);
    } else {
      std::memcpy(&t[4 * c], &v[c], 4);
    }
  }
  return t;
}

// What a shader reads from a texel of format `f` holding bytes `t`.
inline glm::vec4 decode(format f, const texel& t) {
  const format_info fi = info(f);
  glm::vec4 v(0.0f, 0.0f, 0.0f, 1.0f);
  if (f == format::rgb10a2) {
    std::uint32_t word = 0;
    for (int i = 0; i < 4; ++i) word |= std::uint32_t(t[i]) << (8 * i);
    return {unorm_decode(word & 0x3ffu, 10), unorm_decode((word >> 10) & 0x3ffu, 10),
            unorm_decode((word >> 20) & 0x3ffu, 10), unorm_decode(word >> 30, 2)};
  }
  for (int c = 0; c < fi.channels; ++c) {
    if (fi.kind == channel_kind::unorm) {
      v[c] = unorm_decode(t[c], 8);
    } else if (fi.bits[c] == 16) {
      v[c] = half_decode(std::uint16_t(t[2 * c] | (t[2 * c + 1] << 8)));
    } else {
      std::memcpy(&v[c], &t[4 * c], 4);
    }
  }
  return v;
}

namespace detail {
// Halves ordered by value (+0 and -0 alike), so that a step of 1 reaches the next half.
inline int half_order(std::uint16_t h) { return (h & 0x8000u) ? -int(h & 0x7fffu) : int(h & 0x7fffu); }
inline std::uint16_t half_from_order(int k) { return std::uint16_t(k < 0 ? 0x8000u | std::uint32_t(-k) : std::uint32_t(k)); }

inline bool unorm_permitted(float v, std::uint32_t code, int bits) {
  if (std::isnan(v)) return code == 0u;
  const double r = (v < 0.0f ? 0.0 : v > 1.0f ? 1.0 : double(v)) * double((1u << bits) - 1u);
  return code == std::uint32_t(std::floor(r)) || code == std::uint32_t(std::ceil(r));
}

inline bool half_permitted(float v, std::uint16_t h) {
  const float s = half_decode(h);
  if (std::isnan(v)) return std::isnan(s);
  if (std::isnan(s)) return false;
  if (s == v) return true;
  // v must lie strictly between the stored half and the next half towards v.
  const int k = half_order(h) + (v > s ? 1 : -1);
  if (k > 0x7c00 || k < -0x7c00) return false;
  const float next = half_decode(half_from_order(k));
  return (v > s && v < next) || (v < s && v > next);
}
}  // namespace detail

// Whether bytes `stored` are a result the GL and Vulkan rules permit for a shader writing `v` to a
// target of format `f` (see the top of this header).
inline bool permitted(format f, glm::vec4 v, const texel& stored) {
  const format_info fi = info(f);
  if (f == format::rgb10a2) {
    std::uint32_t word = 0;
    for (int i = 0; i < 4; ++i) word |= std::uint32_t(stored[std::size_t(i)]) << (8 * i);
    return detail::unorm_permitted(v.x, word & 0x3ffu, 10) && detail::unorm_permitted(v.y, (word >> 10) & 0x3ffu, 10) &&
           detail::unorm_permitted(v.z, (word >> 20) & 0x3ffu, 10) && detail::unorm_permitted(v.w, word >> 30, 2);
  }
  for (int c = 0; c < fi.channels; ++c) {
    const std::size_t i = std::size_t(c);
    if (fi.kind == channel_kind::unorm) {
      if (!detail::unorm_permitted(v[c], stored[i], 8)) return false;
    } else if (fi.bits[i] == 16) {
      if (!detail::half_permitted(v[c], std::uint16_t(stored[2 * i] | (stored[2 * i + 1] << 8)))) return false;
    } else {
      float s;
      std::memcpy(&s, &stored[4 * i], 4);
      if (std::isnan(v[c]) ? !std::isnan(s) : std::memcmp(&s, &v[c], 4) != 0) return false;
    }
  }
  return true;
}

// What a shader reads back after writing `v` to a target of format `f`.
inline glm::vec4 quantize(format f, glm::vec4 v) { return decode(f, encode(f, v)); }

}  // namespace dstrans

// The scene's textures as the one RGBA8 2D array texture the geometry passes sample (effect::textures),
// with its mip levels, made once here for both backends: texture i is layer i, every texture resampled to
// one size, the largest width and the largest height among them, each at most `largest` texels.
//
//   const dstrans::texture_array a = dstrans::texture_array_of(scene);
//   for (int l = 0; l < int(a.levels.size()); ++l)
//     upload(l, a.level_size(l), a.layers, a.levels[l].data());  // GL: glTextureSubImage3D; Vulkan: a copy
//
// Why one array: a fragment's material picks its layer, so one binding serves every draw of a pass, as the
// materials' block does, and the engine's geometry callback binds nothing per material. The wrap modes
// differ per texture, so the shader wraps the coordinates itself (dst_wrap) and the sampler repeats.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene.hpp"

namespace dstrans {

struct texture_array {
  int width = 0, height = 0, layers = 0;
  // levels[l]: every layer's level_size(l) texels, layer after layer, rows from the top, 4 bytes each.
  std::vector<std::vector<std::uint8_t>> levels;
  // Level l's size: halved per level (rounded down), at least 1.
  glm::ivec2 level_size(int l) const { return glm::max(glm::ivec2(width >> l, height >> l), glm::ivec2(1)); }
};

namespace detail {
// Where texel (x, y) of an image `width` texels wide starts, in bytes.
inline std::size_t texel_at(int x, int y, int width) { return (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4u; }

// Texture `t` resampled to w x h: each texel averages n x n bilinear samples spread over its footprint in
// `t` (n: how many of t's texels the footprint spans, at least 1), so that shrinking does not alias.
inline std::vector<std::uint8_t> resampled(const texture& t, int w, int h) {
  if (t.width == w && t.height == h) return t.rgba;
  std::vector<std::uint8_t> out(std::size_t(w) * std::size_t(h) * 4u);
  const double sx = double(t.width) / w, sy = double(t.height) / h;
  const int nx = std::max(1, int(std::ceil(sx))), ny = std::max(1, int(std::ceil(sy)));
  auto add = [&](glm::dvec4& sum, int x, int y, double weight) {
    const std::uint8_t* p = &t.rgba[texel_at(std::clamp(x, 0, t.width - 1), std::clamp(y, 0, t.height - 1), t.width)];
    sum += weight * glm::dvec4(p[0], p[1], p[2], p[3]);
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      glm::dvec4 sum(0.0);
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const double u = (x + (i + 0.5) / nx) * sx - 0.5, v = (y + (j + 0.5) / ny) * sy - 0.5;
          const double fu = std::floor(u), fv = std::floor(v), a = u - fu, b = v - fv;
          const int iu = int(fu), iv = int(fv);
          add(sum, iu, iv, (1 - a) * (1 - b));
          add(sum, iu + 1, iv, a * (1 - b));
          add(sum, iu, iv + 1, (1 - a) * b);
          add(sum, iu + 1, iv + 1, a * b);
        }
      sum /= double(nx * ny);
      for (int c = 0; c < 4; ++c) out[texel_at(x, y, w) + std::size_t(c)] = std::uint8_t(std::lround(std::clamp(sum[c], 0.0, 255.0)));
    }
  return out;
}

// The next mip level of one layer of `from` (from_size) at `to` (to_size): each texel the mean of the 2 x 2
// it covers (an odd edge repeats its last row or column).
inline void halve(const std::uint8_t* from, glm::ivec2 from_size, std::uint8_t* to, glm::ivec2 to_size) {
  for (int y = 0; y < to_size.y; ++y)
    for (int x = 0; x < to_size.x; ++x)
      for (int c = 0; c < 4; ++c) {
        int sum = 0;
        for (int j = 0; j < 2; ++j)
          for (int i = 0; i < 2; ++i) {
            const int fx = std::min(2 * x + i, from_size.x - 1), fy = std::min(2 * y + j, from_size.y - 1);
            sum += from[texel_at(fx, fy, from_size.x) + std::size_t(c)];
          }
        to[texel_at(x, y, to_size.x) + std::size_t(c)] = std::uint8_t((sum + 2) / 4);
      }
}
}  // namespace detail

// The layers' size and count of texture_array_of(s, largest), and no texels.
inline texture_array texture_array_shape(const scene& s, int largest = 1024) {
  texture_array a;
  a.width = a.height = 1;
  for (const texture& t : s.textures)
    if (t.valid()) {
      a.width = std::max(a.width, std::min(t.width, largest));
      a.height = std::max(a.height, std::min(t.height, largest));
    }
  a.layers = std::max<int>(int(s.textures.size()), 1);
  return a;
}

// The bytes of every level of every layer of texture_array_of(s, largest).
inline std::size_t texture_array_bytes(const scene& s, int largest = 1024) {
  const texture_array a = texture_array_shape(s, largest);
  std::size_t bytes = 0;
  for (int l = 0;; ++l) {
    const glm::ivec2 size = a.level_size(l);
    bytes += std::size_t(size.x) * std::size_t(size.y) * 4u * std::size_t(a.layers);
    if (size == glm::ivec2(1)) return bytes;
  }
}

// The textures of `s` as one array with every mip level down to 1 x 1. An invalid texture (texture::valid)
// gives a white layer; a scene without textures one white 1 x 1 layer, for a frame that forces the effect.
inline texture_array texture_array_of(const scene& s, int largest = 1024) {
  texture_array a = texture_array_shape(s, largest);
  const std::size_t layer_bytes = std::size_t(a.width) * std::size_t(a.height) * 4u;
  a.levels.emplace_back(layer_bytes * std::size_t(a.layers), std::uint8_t(255));
  for (std::size_t i = 0; i < s.textures.size(); ++i)
    if (s.textures[i].valid()) {
      const std::vector<std::uint8_t> texels = detail::resampled(s.textures[i], a.width, a.height);
      std::copy(texels.begin(), texels.end(), a.levels[0].begin() + std::ptrdiff_t(i * layer_bytes));
    }
  for (int l = 1; a.level_size(l - 1) != glm::ivec2(1); ++l) {
    const glm::ivec2 from = a.level_size(l - 1), to = a.level_size(l);
    const std::size_t from_bytes = std::size_t(from.x) * std::size_t(from.y) * 4u, to_bytes = std::size_t(to.x) * std::size_t(to.y) * 4u;
    a.levels.emplace_back(to_bytes * std::size_t(a.layers));
    for (std::size_t k = 0; k < std::size_t(a.layers); ++k)
      detail::halve(a.levels[std::size_t(l - 1)].data() + k * from_bytes, from, a.levels[std::size_t(l)].data() + k * to_bytes, to);
  }
  return a;
}

}  // namespace dstrans

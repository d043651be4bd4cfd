// Checks that the GL and Vulkan tests share: formula agreement and the bit-exact G-buffer write.
#pragma once

#include <catch2/catch.hpp>

#include <functional>
#include <iterator>
#include <random>

#include <dstrans/dstrans.hpp>

#include "agreement.hpp"

namespace dstrans::testing {

using gpu_runner = std::function<result<words>(const formula&, const words&, std::size_t)>;

// Every formula, 10,000 calls (16 edge calls, NaN and infinities in each float scalar alone, then random), on
// the GPU and the CPU: they agree.
inline void check_every_formula(const gpu_runner& gpu) {
  for (const formula& f : formulas()) {
    const std::size_t calls = 10000;
    const words args = random_args(f, calls, 20261122u);
    const words cpu = run_cpu(f, args, calls);
    const auto out = gpu(f, args, calls);
    INFO(f.name);
    REQUIRE(out);
    REQUIRE(out->size() == cpu.size());
    const std::size_t n = std::size_t(f.result.word_count());
    std::size_t wrong = 0;
    std::string first;
    for (std::size_t i = 0; i < calls; ++i) {
      std::string why;
      if (!agrees(f.result, cpu.data() + i * n, out->data() + i * n, tolerance_exponent(f), why, f.packed_field_bits)) {
        if (!wrong++) first = "call " + std::to_string(i) + ": " + why;
      }
    }
    INFO("first disagreement: " << first);
    CHECK(wrong == 0);
  }
}

// More calls than one dispatch may have on Mesa (65,535 groups of 64): the runner splits them, and every
// call's result is the CPU's (a dispatch past the limit returns zeros and no error).
inline void check_large_batch(const gpu_runner& gpu) {
  const formula* f = find_formula("dst_unorm8");
  REQUIRE(f);
  const std::size_t calls = 65535u * 64u + 1000u;
  words args;
  for (std::size_t i = 0; i < calls; ++i) put(float(i % 1021) / 1020.0f, args);
  const auto out = gpu(*f, args, calls);
  REQUIRE(out);
  REQUIRE(out->size() == calls);
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < calls; ++i) wrong += (*out)[i] != shader::dst_unorm8(float(i % 1021) / 1020.0f);
  CHECK(wrong == 0);
}

// Alphas at the edges of "transparent": just below 1 (which rounding alone would store as opaque) and
// just above 0, then 1.
inline constexpr float boundary_alphas[] = {1.0f - 0x1p-24f, 0.999f, 254.5f / 255.0f, 1.0f / 255.0f, 0.5f / 255.0f, 0.0f, 1.0f};

// The surfaces a G-buffer test writes, one a pixel: random, plus rows of hard values (exact UNORM
// ties, values a float rounding away from a tie, out of range, NaN, axis normals, boundary alphas, every
// integer power).
inline std::vector<surface> test_surfaces(int width, int height) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), sym(-1.0f, 1.0f);
  std::vector<surface> out;
  for (int i = 0; i < width * height; ++i) {
    surface s = shader::dst_surface_zero();
    s.diffuse = {unit(rng), unit(rng), unit(rng)};
    s.alpha = unit(rng);
    s.normal = glm::normalize(glm::vec3(sym(rng), sym(rng), sym(rng)) + glm::vec3(0.0f, 0.0f, 1e-3f));
    s.spec_intensity = unit(rng);
    s.spec_power = float(i % 256);
    s.depth = unit(rng);
    const int k = i % 256;
    switch ((i / width) % 7) {
      case 0: s.diffuse = glm::vec3((float(k) + 0.5f) / 255.0f); break;  // near a tie, rounded as a float
      case 1: s.diffuse = glm::vec3(float(k) / 255.0f); s.alpha = 0.5f; break;
      case 2: s.normal = glm::vec3(0.0f, 0.0f, k % 2 ? 1.0f : -1.0f); break;  // 511.5: an exact tie
      case 3: s.diffuse = {-0.5f, 1.5f, 1.0f}; s.spec_intensity = 2.0f; break;
      case 4: s.diffuse = {NAN, 0.5f, 70000.0f}; s.alpha = -NAN; s.depth = NAN; break;
      case 5: s.alpha = boundary_alphas[std::size_t(k) % std::size(boundary_alphas)]; break;  // just below 1 and 0
      default: break;
    }
    out.push_back(s);
  }
  return out;
}

// GLSL for a fragment shader that writes surface number (row * width + column) of a storage buffer at
// binding 0 through layout L's generated write path.
template <class L>
glsl::source gbuffer_writer(int width) {
  glsl::source src;
  glsl::layout_options opt;
  opt.sides = glsl::side::write;
  glsl::add_layout<L>(src, "gbuffer", opt);
  std::string code =
      "layout(std430, binding = 0) readonly buffer surfaces { uint dst_in[]; };\n"
      "void main() {\n"
      "  ivec2 p = ivec2(gl_FragCoord.xy);\n"
      "  uint base = uint(p.y * " + std::to_string(width) + " + p.x) * 10u;\n"
      "  dst_surface s;\n";
  int at = 0;
  glsl::load_value(value_traits<surface>::type(), "s", at, code);
  code += "  dst_gbuffer_write(s);\n}\n";
  src.add(code, __FILE__, __LINE__);
  return src;
}

// Checks what the GPU stored for `surfaces` against the CPU: bit for bit with dstrans::write when
// `exact` (the surfaces are on the layout's grid, where the rules leave no choice), and otherwise within
// what the GL and Vulkan rules permit for the CPU's channel values (dstrans::permitted).
template <class L>
void check_texels(const std::vector<surface>& surfaces, bool exact, const std::function<std::vector<texel>(int)>& read_target) {
  for (int t = 0; t < L::target_count; ++t) {
    const format f = L::formats[std::size_t(t)];
    const std::vector<texel> gpu = read_target(t);
    REQUIRE(gpu.size() == surfaces.size());
    const std::size_t bpp = std::size_t(info(f).bytes_per_pixel);
    std::size_t wrong = 0;
    std::string first;
    for (std::size_t i = 0; i < surfaces.size(); ++i) {
      const texel cpu = write<L>(surfaces[i])[std::size_t(t)];
      const bool ok = exact ? std::memcmp(cpu.data(), gpu[i].data(), bpp) == 0
                            : permitted(f, pack<L>(surfaces[i])[std::size_t(t)], gpu[i]);
      if (!ok && !wrong++) {
        first = "pixel " + std::to_string(i) + ": cpu";
        for (std::size_t b = 0; b < bpp; ++b) first += " " + std::to_string(cpu[b]);
        first += ", gpu";
        for (std::size_t b = 0; b < bpp; ++b) first += " " + std::to_string(gpu[i][b]);
      }
    }
    INFO("target " << t << " (" << info(f).name << (exact ? ", bit for bit" : ", permitted") << "), first difference: " << first);
    CHECK(wrong == 0);
  }
  // The normals the GPU stored come back within the layout's angular error (Table 3.1's 10 bits: 0.1
  // degrees; the compact layout's octahedral 8 bits: 0.94 on the CPU, one permitted code more on a GPU).
  if constexpr (L::template stores<field::normal>()) {
    std::vector<std::vector<texel>> all;
    for (int t = 0; t < L::target_count; ++t) all.push_back(read_target(t));
    float worst = 0.0f;
    for (std::size_t i = 0; i < surfaces.size(); ++i) {
      if (!(std::abs(glm::length(surfaces[i].normal) - 1.0f) < 1e-2f)) continue;  // the on-grid ones are near unit
      const glm::vec3 n = glm::normalize(surfaces[i].normal);
      std::array<texel, L::target_count> px;
      for (int t = 0; t < L::target_count; ++t) px[std::size_t(t)] = all[std::size_t(t)][i];
      const glm::vec3 back = glm::normalize(read<L>(px).normal);
      worst = std::max(worst, glm::degrees(std::acos(std::min(1.0f, glm::dot(n, back)))));
    }
    INFO("worst angular error of the stored normals: " << worst << " degrees, layout of " << L::bytes_per_pixel << " bytes");
    CHECK(worst < 1.5f);
  }
}

// `surfaces` moved onto layout L's grid: what reading a G-buffer written with them gives.
template <class L>
std::vector<surface> on_grid(const std::vector<surface>& surfaces) {
  std::vector<surface> out;
  for (const surface& s : surfaces) out.push_back(read<L>(write<L>(s)));
  return out;
}

// A counter-clockwise triangle (clip space, y up) over the lower left half of clip space, which paints
// red where it is front-facing and green where not: with back faces culled it must appear, red, in the
// image's bottom rows on both backends.
inline const char* const facing_vertex_shader =
    "#ifdef VULKAN\n#define DST_VERTEX_ID gl_VertexIndex\n#else\n#define DST_VERTEX_ID gl_VertexID\n#endif\n"
    "void main() {\n"
    "  vec2 corners[3] = vec2[](vec2(-1.0f, -1.0f), vec2(1.0f, -1.0f), vec2(-1.0f, 1.0f));\n"
    "  gl_Position = vec4(corners[DST_VERTEX_ID], 0.0f, 1.0f);\n"
    "}\n";
inline const char* const facing_fragment_shader =
    "layout(location = 0) out vec4 colour;\n"
    "void main() { colour = gl_FrontFacing ? vec4(1.0f, 0.0f, 0.0f, 1.0f) : vec4(0.0f, 1.0f, 0.0f, 1.0f); }\n";

inline void check_facing(const std::vector<texel>& texels, int size) {
  const texel& bottom_left = texels[std::size_t((size - 1) * size)];
  const texel& top_right = texels[std::size_t(size - 1)];
  CHECK(int(bottom_left[0]) == 255);  // drawn, front-facing
  CHECK(int(bottom_left[1]) == 0);
  CHECK(int(top_right[0]) == 0);      // outside the triangle
}

// A second layout for the bit-exact test: half and full floats, a two-channel target.
using float_layout = layout<surface, target<format::rgba16f, field::normal, field::alpha>,
                            target<format::rgba32f, field::diffuse, field::depth>,
                            target<format::rg16f, field::spec_intensity, field::spec_power>>;

}  // namespace dstrans::testing

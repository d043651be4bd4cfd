// What "the GPU computes what the C++ computes" means for each formula, and the inputs it is checked on.
//
// Tolerance: results of integer and bool type must be identical. Float results must be identical in
// class (both NaN, or the same infinity) and otherwise differ by at most 2^-20 of max(1, |cpu|), about
// 8 units in the last place of a float. The reason: GLSL lets a compiler contract a*b+c into one fma and
// reassociate (the formulas do not use `precise`), and Mesa does; the C++ side, built for baseline
// x86-64, has no fma instruction and never contracts. One contraction moves a result by at most half an
// ulp of the larger intermediate term, and the shared formulas are short expressions, so a few ulps bound
// every honest difference. Anything larger is a bug.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <string>

#include <dstrans/formula.hpp>

namespace dstrans::testing {

// Packed arguments for `calls` calls of f: the first 16 calls take their scalars from edge lists
// (0, -0, 1, -1, 0.5, 255, tiny, huge, infinities, NaN; 0, 1, -1, 2, 7, 8, INT_MAX, INT_MIN), rotating
// so that each argument meets each edge value; the rest are random (floats in [-4, 4], ints in [-2, 64]).
inline words random_args(const formula& f, std::size_t calls, std::uint32_t seed) {
  static const float float_edges[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 255.0f, 1e-7f, 1e7f, INFINITY, -INFINITY, NAN};
  static const int int_edges[] = {0, 1, -1, 2, 7, 8, 2147483647, -2147483647 - 1};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> real(-4.0f, 4.0f);
  std::uniform_int_distribution<int> small(-2, 64);
  words out;
  for (std::size_t call = 0; call < calls; ++call) {
    const bool edge = call < 16;
    std::size_t scalar = 0;  // the scalar's position within this call
    std::function<void(const value_type&)> gen = [&](const value_type& t) {
      if (t.kind == value_kind::record) {
        for (const auto& fld : t.fields) gen(fld.second);
        return;
      }
      for (int k = 0; k < t.word_count(); ++k, ++scalar) {
        const std::size_t e = call + scalar;
        switch (t.kind) {
          case value_kind::int_: case value_kind::ivec2: put(edge ? int_edges[e % 8] : small(rng), out); break;
          case value_kind::uint_: put(edge ? unsigned(int_edges[e % 8]) : unsigned(rng()), out); break;
          case value_kind::bool_: put(edge ? (e & 1u) != 0u : (rng() & 1u) != 0u, out); break;
          default: put(edge ? float_edges[e % 11] : real(rng), out);
        }
      }
    };
    for (const auto& a : f.args) gen(a.second);
  }
  return out;
}

// Whether `gpu` agrees with `cpu` for a value of type t starting at word `at` (see the tolerance above).
inline bool agrees(const value_type& t, const std::uint32_t* cpu, const std::uint32_t* gpu, std::string& why) {
  if (t.kind == value_kind::record) {
    for (const auto& fld : t.fields) {
      if (!agrees(fld.second, cpu, gpu, why)) {
        why = fld.first + ": " + why;
        return false;
      }
      cpu += fld.second.word_count();
      gpu += fld.second.word_count();
    }
    return true;
  }
  for (int k = 0; k < t.word_count(); ++k) {
    if (!t.is_float()) {
      if (cpu[k] != gpu[k]) {
        why = "component " + std::to_string(k) + ": cpu " + std::to_string(int(cpu[k])) + ", gpu " + std::to_string(int(gpu[k]));
        return false;
      }
      continue;
    }
    const std::uint32_t* c = cpu + k;
    const std::uint32_t* g = gpu + k;
    const float a = value_traits<float>::get(c), b = value_traits<float>::get(g);
    const bool same_class = std::isnan(a) ? std::isnan(b) : std::isinf(a) ? (std::isinf(b) && (a > 0) == (b > 0)) : std::isfinite(b);
    if (!same_class || (std::isfinite(a) && std::fabs(a - b) > std::ldexp(std::fmax(1.0f, std::fabs(a)), -20))) {
      why = "component " + std::to_string(k) + ": cpu " + std::to_string(a) + ", gpu " + std::to_string(b);
      return false;
    }
  }
  return true;
}

}  // namespace dstrans::testing

// What "the GPU computes what the C++ computes" means for each formula, and the inputs it is checked on.
//
// Tolerance: results of integer and bool type must be identical. Float results must be identical in
// class (both NaN, or the same infinity) and otherwise differ by at most 2^-20 of max(1, |cpu|), about
// 8 units in the last place of a float. The reason: GLSL lets a compiler contract a*b+c into one fma and
// reassociate (the formulas do not use `precise`), and Mesa does; the C++ side, built for baseline
// x86-64, has no fma instruction and never contracts. One contraction moves a result by at most half an
// ulp of the larger intermediate term, and the shared formulas are short expressions, so a few ulps bound
// every honest difference. Anything larger is a bug.
// Formulas that call GLSL's transcendental built-ins (pow, exp2, log2, sqrt, ...) get 2^-16 instead:
// GLSL only promises exp2 and log2 to 3 ulp and defines pow(x, y) as exp2(y log2 x), so pow's relative
// error grows with |y log2 x|; llvmpipe's pow is measured at 1.1e-6 (2^-19.8) on these inputs, and 2^-16
// leaves room for other conforming drivers without hiding a wrong formula (which is off by far more).
#pragma once

#include <cctype>
#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <string>

#include <dstrans/formula.hpp>

namespace dstrans::testing {

// The number of float scalars (vector components and record fields included) in one call of f.
inline std::size_t float_scalars(const formula& f) {
  std::function<std::size_t(const value_type&)> count = [&](const value_type& t) -> std::size_t {
    if (t.kind == value_kind::record) {
      std::size_t n = 0;
      for (const auto& fld : t.fields) n += count(fld.second);
      return n;
    }
    return t.is_float() ? std::size_t(t.word_count()) : 0u;
  };
  std::size_t n = 0;
  for (const auto& a : f.args) n += count(a.second);
  return n;
}

// How many calls random_args gives NaN or an infinity in one float scalar alone: three a scalar.
inline std::size_t special_calls(const formula& f) { return 3 * float_scalars(f); }

// Packed arguments for `calls` calls of f: the first `edge_calls` calls take their scalars from edge lists
// (0, -0, 1, -1, 0.5, 255, tiny, huge, infinities, NaN; 0, 1, -1, 2, 7, 8, INT_MAX, INT_MIN), rotating
// so that each argument meets each edge value; with `specials`, the next special_calls(f) put NaN, +inf and
// -inf in each float scalar (every vector component, every record field) in turn, the others random
// within their domains, so that every NaN and infinity a formula can meet alone is met; the rest are
// random within each argument's domain (formula::domains: floats in [lo, hi] or unit vectors; ints in
// [-2, 64]).
inline words random_args(const formula& f, std::size_t calls, std::uint32_t seed, std::size_t edge_calls = 16,
                         bool specials = true) {
  static const float float_edges[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 255.0f, 1e-7f, 1e7f, INFINITY, -INFINITY, NAN};
  static const float special_values[] = {NAN, INFINITY, -INFINITY};
  static const int int_edges[] = {0, 1, -1, 2, 7, 8, 2147483647, -2147483647 - 1};
  const std::size_t special_end = edge_calls + (specials ? special_calls(f) : 0u);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> small(-2, 64);
  words out;
  for (std::size_t call = 0; call < calls; ++call) {
    const bool edge = call < edge_calls;
    const bool special = !edge && call < special_end;
    const std::size_t special_slot = special ? (call - edge_calls) / 3 : ~std::size_t(0);
    const float special_value = special ? special_values[(call - edge_calls) % 3] : 0.0f;
    std::size_t scalar = 0;  // the scalar's position within this call
    std::size_t float_slot = 0;  // the float scalar's position within this call
    input_range range;
    std::function<void(const value_type&)> gen = [&](const value_type& t) {
      if (t.kind == value_kind::record) {
        for (const auto& fld : t.fields) gen(fld.second);
        return;
      }
      std::uniform_real_distribution<float> real(range.lo, range.hi);
      if (range.unit && !edge && t.kind == value_kind::vec3) {
        glm::vec3 v;
        do v = {real(rng), real(rng), real(rng)};
        while (glm::dot(v, v) < 1e-4f || glm::dot(v, v) > 1.0f);
        v = glm::normalize(v);
        for (int k = 0; k < 3; ++k, ++float_slot)
          if (float_slot == special_slot) v[k] = special_value;
        put(v, out);
        scalar += 3;
        return;
      }
      for (int k = 0; k < t.word_count(); ++k, ++scalar) {
        const std::size_t e = call + scalar;
        switch (t.kind) {
          case value_kind::int_: case value_kind::ivec2: put(edge ? int_edges[e % 8] : small(rng), out); break;
          case value_kind::uint_: put(edge ? unsigned(int_edges[e % 8]) : unsigned(rng()), out); break;
          case value_kind::bool_: put(edge ? (e & 1u) != 0u : (rng() & 1u) != 0u, out); break;
          default: {
            const float x = edge ? float_edges[e % 11] : real(rng);
            put(float_slot++ == special_slot ? special_value : x, out);
          }
        }
      }
    };
    for (std::size_t i = 0; i < f.args.size(); ++i) {
      range = f.domains[i];
      gen(f.args[i].second);
    }
  }
  return out;
}

// The relative tolerance for formula f's float results (see above).
inline int tolerance_exponent(const formula& f) {
  const std::string code = f.block->code;
  for (const char* fn : {"pow", "exp", "exp2", "log", "log2", "sqrt", "inversesqrt", "normalize", "length", "distance",
                         "sin", "cos", "tan", "asin", "acos", "atan"})
    for (std::size_t at = code.find(std::string(fn) + "("); at != std::string::npos; at = code.find(std::string(fn) + "(", at + 1))
      if (at == 0 || !(std::isalnum(static_cast<unsigned char>(code[at - 1])) || code[at - 1] == '_')) return -16;
  return -20;
}

// Whether two packed words agree field by field within one code (formula::packed_field_bits).
inline bool codes_agree(std::uint32_t a, std::uint32_t b, int bits) {
  for (int at = 0; at < 32; at += bits) {
    const long x = long((a >> at) & ((1ull << bits) - 1u)), y = long((b >> at) & ((1ull << bits) - 1u));
    if (std::labs(x - y) > 1) return false;
  }
  return true;
}

// Whether `gpu` agrees with `cpu` for a value of type t within 2^exponent of max(1, |cpu|); integers
// exactly, or within one code per field for results that pack `packed_bits`-wide codes.
inline bool agrees(const value_type& t, const std::uint32_t* cpu, const std::uint32_t* gpu, int exponent, std::string& why,
                   int packed_bits = 0) {
  if (t.kind == value_kind::record) {
    for (const auto& fld : t.fields) {
      if (!agrees(fld.second, cpu, gpu, exponent, why)) {
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
      if (packed_bits ? !codes_agree(cpu[k], gpu[k], packed_bits) : cpu[k] != gpu[k]) {
        why = "component " + std::to_string(k) + ": cpu " + std::to_string(int(cpu[k])) + ", gpu " + std::to_string(int(gpu[k]));
        return false;
      }
      continue;
    }
    const std::uint32_t* c = cpu + k;
    const std::uint32_t* g = gpu + k;
    const float a = value_traits<float>::get(c), b = value_traits<float>::get(g);
    const bool same_class = std::isnan(a) ? std::isnan(b) : std::isinf(a) ? (std::isinf(b) && (a > 0) == (b > 0)) : std::isfinite(b);
    if (!same_class || (std::isfinite(a) && std::fabs(a - b) > std::ldexp(std::fmax(1.0f, std::fabs(a)), exponent))) {
      why = "component " + std::to_string(k) + ": cpu " + std::to_string(a) + ", gpu " + std::to_string(b);
      return false;
    }
  }
  return true;
}

// The hard cases' property: for arguments within their domains, every float of every result is finite
// and within the formula's promised range (formula::yields). Returns the number of calls that break it
// and describes the first in `why`.
inline std::size_t broken_properties(const formula& f, const words& results, std::size_t calls, std::string& why) {
  std::size_t broken = 0;
  const std::size_t n = std::size_t(f.result.word_count());
  std::function<void(const value_type&, const std::uint32_t*&, bool&, std::string&)> walk =
      [&](const value_type& t, const std::uint32_t*& p, bool& ok, std::string& what) {
        if (t.kind == value_kind::record) {
          for (const auto& fld : t.fields) walk(fld.second, p, ok, what);
          return;
        }
        for (int k = 0; k < t.word_count(); ++k) {
          if (!t.is_float()) {
            ++p;
            continue;
          }
          const float v = value_traits<float>::get(p);
          if (!std::isfinite(v) || v < f.result_lo || v > f.result_hi) {
            ok = false;
            what = std::to_string(v);
          }
        }
      };
  for (std::size_t i = 0; i < calls; ++i) {
    const std::uint32_t* p = results.data() + i * n;
    bool ok = true;
    std::string what;
    walk(f.result, p, ok, what);
    if (!ok && !broken++) why = "call " + std::to_string(i) + " gives " + what;
  }
  return broken;
}

// Every formula, 100,000 calls within its domains through `run`: no result breaks its property.
template <class Run>
void check_every_property(Run&& run) {
  for (const formula& f : formulas()) {
    const std::size_t calls = 100000;
    const words args = random_args(f, calls, 6u, 0, false);
    const auto results = run(f, args, calls);
    INFO(f.name);
    REQUIRE(results);
    std::string why;
    const std::size_t broken = broken_properties(f, *results, calls, why);
    INFO("first: " << why);
    CHECK(broken == 0);
  }
}

}  // namespace dstrans::testing

// Every shared formula, callable by name with values packed as 32-bit words: the CPU evaluates the C++
// side of the shared text, and add_formula_kernel emits a compute shader that evaluates the GLSL side,
// so a backend can run both over the same inputs (dstrans eval, and the CPU/GPU agreement tests).
//
//   const dstrans::formula* f = dstrans::find_formula("dst_rows_partner");
//   dstrans::words in;                       // the arguments of one call, in order
//   dstrans::put(glm::ivec2(3, 0), in);
//   dstrans::put(glm::ivec2(8, 8), in);
//   dstrans::words out = f->cpu(in);         // ivec2(3, 1), as 2 words
//   dstrans::glsl::source cs;
//   dstrans::glsl::add_formula_kernel(cs, *f);   // the same call on a GPU, over many inputs
#pragma once

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <functional>
#include <initializer_list>
#include <tuple>
#include <string>
#include <utility>
#include <vector>

#include "fullscreen.hpp"
#include "glsl.hpp"
#include "interlace.hpp"
#include "kbuffer.hpp"
#include "light_basis.hpp"
#include "light_volume.hpp"
#include "post.hpp"
#include "phong.hpp"
#include "refraction.hpp"
#include "surface.hpp"
#include "transparent_shadow.hpp"

namespace dstrans {

// A value as 32-bit words: floats by their bits, ints as two's complement, bools as 0 or 1, vectors by
// component, records by member in declaration order.
using words = std::vector<std::uint32_t>;

enum class value_kind { float_, vec2, vec3, vec4, int_, ivec2, uint_, bool_, record };

// The type of a formula's argument or result.
struct value_type {
  value_kind kind = value_kind::float_;
  std::string record_name;                                // the GLSL struct, for records
  std::vector<std::pair<std::string, value_type>> fields;  // the members, for records

  // How many words a value of this type takes.
  int word_count() const {
    switch (kind) {
      case value_kind::vec2: case value_kind::ivec2: return 2;
      case value_kind::vec3: return 3;
      case value_kind::vec4: return 4;
      case value_kind::record: {
        int n = 0;
        for (const auto& f : fields) n += f.second.word_count();
        return n;
      }
      default: return 1;
    }
  }
  // The GLSL (and dstrans eval) name: float, vec3, ivec2, uint, bool, or the struct's name.
  std::string name() const {
    static const char* const names[] = {"float", "vec2", "vec3", "vec4", "int", "ivec2", "uint", "bool"};
    return kind == value_kind::record ? record_name : names[int(kind)];
  }
  // Whether values are floating point (compared within a tolerance) rather than exact.
  bool is_float() const { return kind <= value_kind::vec4; }
};

template <class T>
struct value_traits;

namespace detail {
inline std::uint32_t float_bits(float v) {
  std::uint32_t w;
  std::memcpy(&w, &v, 4);
  return w;
}
inline float bits_float(std::uint32_t w) {
  float v;
  std::memcpy(&v, &w, 4);
  return v;
}
}  // namespace detail

template <>
struct value_traits<float> {
  static value_type type() { return {value_kind::float_, {}, {}}; }
  static void put(float v, words& w) { w.push_back(detail::float_bits(v)); }
  static float get(const std::uint32_t*& p) { return detail::bits_float(*p++); }
};
template <>
struct value_traits<int> {
  static value_type type() { return {value_kind::int_, {}, {}}; }
  static void put(int v, words& w) { w.push_back(std::uint32_t(v)); }
  static int get(const std::uint32_t*& p) { return int(*p++); }
};
template <>
struct value_traits<unsigned> {
  static value_type type() { return {value_kind::uint_, {}, {}}; }
  static void put(unsigned v, words& w) { w.push_back(v); }
  static unsigned get(const std::uint32_t*& p) { return *p++; }
};
template <>
struct value_traits<bool> {
  static value_type type() { return {value_kind::bool_, {}, {}}; }
  static void put(bool v, words& w) { w.push_back(v ? 1u : 0u); }
  static bool get(const std::uint32_t*& p) { return *p++ != 0u; }
};
template <glm::length_t L, class T>
struct value_traits<glm::vec<L, T>> {
  static value_type type() {
    if constexpr (std::is_same_v<T, int>) {
      static_assert(L == 2, "dstrans formulas take ivec2 as their only integer vector");
      return {value_kind::ivec2, {}, {}};
    } else {
      return {L == 2 ? value_kind::vec2 : L == 3 ? value_kind::vec3 : value_kind::vec4, {}, {}};
    }
  }
  static void put(const glm::vec<L, T>& v, words& w) {
    for (glm::length_t i = 0; i < L; ++i) value_traits<T>::put(v[i], w);
  }
  static glm::vec<L, T> get(const std::uint32_t*& p) {
    glm::vec<L, T> v;
    for (glm::length_t i = 0; i < L; ++i) v[i] = value_traits<T>::get(p);
    return v;
  }
};

// Records are described by visiting their members in declaration order, once for all three uses.
template <class Record>
struct record_traits {
  template <class R, class Visit>
  static void members(R& r, Visit&& visit);
};
template <>
template <class R, class Visit>
void record_traits<surface>::members(R& r, Visit&& visit) {
  visit("diffuse", r.diffuse);
  visit("alpha", r.alpha);
  visit("normal", r.normal);
  visit("spec_intensity", r.spec_intensity);
  visit("spec_power", r.spec_power);
  visit("depth", r.depth);
}
template <>
template <class R, class Visit>
void record_traits<light_sample>::members(R& r, Visit&& visit) {
  visit("light", r.light);
  visit("specular", r.specular);
}

namespace detail {
template <class R>
struct record_value_traits {
  static value_type type() {
    value_type t{value_kind::record, record_name(), {}};
    R r{};
    record_traits<R>::members(r, [&](const char* n, auto& m) {
      t.fields.emplace_back(n, value_traits<std::decay_t<decltype(m)>>::type());
    });
    return t;
  }
  static void put(const R& r, words& w) {
    record_traits<R>::members(r, [&](const char*, const auto& m) { value_traits<std::decay_t<decltype(m)>>::put(m, w); });
  }
  static R get(const std::uint32_t*& p) {
    R r{};
    record_traits<R>::members(r, [&](const char*, auto& m) { m = value_traits<std::decay_t<decltype(m)>>::get(p); });
    return r;
  }
  static std::string record_name();
};
template <>
inline std::string record_value_traits<surface>::record_name() { return text::dst_surface.name; }
template <>
inline std::string record_value_traits<light_sample>::record_name() { return text::dst_light_sample.name; }
}  // namespace detail

template <>
struct value_traits<surface> : detail::record_value_traits<surface> {};
template <>
struct value_traits<light_sample> : detail::record_value_traits<light_sample> {};

// Appends value `v` to `w`.
template <class T>
void put(const T& v, words& w) {
  value_traits<T>::put(v, w);
}

// The values an argument is meant to take, for tests that draw inputs: floats (and every component of
// a vector) in [lo, hi], or a unit vector. Outside its domain a formula still runs, but its result may
// be ill-conditioned (Phong of non-unit vectors cancels), so CPU and GPU need not agree to a few ulps.
struct input_range {
  float lo = -4.0f, hi = 4.0f;
  bool unit = false;
};
inline input_range unit_vector() { return {-1.0f, 1.0f, true}; }

// A shared function that dstrans eval and the agreement tests can call.
struct formula {
  std::string name;           // the function's name in C++ and GLSL
  const shared_text* block;   // the shared block that defines it
  std::vector<std::pair<std::string, value_type>> args;
  value_type result;
  std::function<words(const words&)> cpu;  // one call: the packed arguments in, the packed result out
  std::vector<input_range> domains;        // one per argument
  // Every float of the result, for arguments within their domains: finite and within [lo, hi] (the
  // physical range: light and colour at least 0, alpha and factors within [0, 1]).
  float result_lo = -INFINITY, result_hi = INFINITY;
  // For results that pack quantised codes (a uint of fields this many bits wide): a GPU's division and
  // fma may put a value on the other side of a rounding boundary, so backends agree within one code.
  int packed_field_bits = 0;

  // This formula with arguments `names` meant to lie in `r`.
  formula within(std::initializer_list<const char*> names, input_range r) && {
    for (const char* arg : names)
      for (std::size_t i = 0; i < args.size(); ++i)
        if (args[i].first == arg) domains[i] = r;
    return std::move(*this);
  }
  formula within(const char* arg, input_range r) && { return std::move(*this).within({arg}, r); }
  // This formula's uint result packing fields `bits` wide.
  formula packs(int bits) && {
    packed_field_bits = bits;
    return std::move(*this);
  }
  // This formula promising results within [lo, hi] for arguments within their domains.
  formula yields(float lo, float hi) && {
    result_lo = lo;
    result_hi = hi;
    return std::move(*this);
  }
};

namespace detail {
// The parameter names of function `fn` in shared code `code`, in order.
inline std::vector<std::string> parameter_names(const std::string& code, const std::string& fn) {
  std::size_t at = 0;
  while ((at = code.find(fn + "(", at)) != std::string::npos && !(at > 0 && code[at - 1] == ' ')) at += fn.size();
  std::vector<std::string> names;
  if (at == std::string::npos) return names;
  // Split the parameter list at its top-level commas; a parameter's name is its last word.
  std::string param;
  auto finish = [&] {
    while (!param.empty() && param.back() == ' ') param.pop_back();
    const std::size_t space = param.find_last_of(" )");
    if (!param.empty()) names.push_back(space == std::string::npos ? param : param.substr(space + 1));
    param.clear();
  };
  int depth = 0;
  for (std::size_t i = at + fn.size() + 1; i < code.size(); ++i) {
    const char c = code[i];
    if (c == '(') ++depth;
    if (c == ')' && depth-- == 0) break;
    if (c == ',' && depth == 0) finish();
    else param += c;
  }
  finish();
  return names;
}

template <class R, class... A, std::size_t... I>
formula make_formula(const shared_text& block, const char* name, R (*fn)(A...), std::index_sequence<I...>) {
  formula f{name, &block, {}, value_traits<R>::type(), {}, std::vector<input_range>(sizeof...(A))};
  const std::vector<std::string> names = parameter_names(block.code, name);
  const value_type types[] = {value_traits<std::decay_t<A>>::type()..., value_traits<R>::type()};
  for (std::size_t i = 0; i < sizeof...(A); ++i) f.args.emplace_back(i < names.size() ? names[i] : "?", types[i]);
  f.cpu = [fn](const words& in) {
    [[maybe_unused]] const std::uint32_t* p = in.data();
    // Braced initialisation evaluates the arguments left to right, as they are packed.
    [[maybe_unused]] std::tuple<std::decay_t<A>...> a{value_traits<std::decay_t<A>>::get(p)...};
    words out;
    put(fn(std::get<I>(a)...), out);
    return out;
  };
  return f;
}
}  // namespace detail

// Formula `fn` of shared block `block`; argument names and types come from the one text and signature.
template <class R, class... A>
formula make_formula(const shared_text& block, const char* name, R (*fn)(A...)) {
  return detail::make_formula(block, name, fn, std::index_sequence_for<A...>{});
}

#define DSTRANS_FORMULA(block, fn) ::dstrans::make_formula(::dstrans::text::block, #fn, &::dstrans::shader::fn)

// Every shared formula of the core. A formula added to a shared block is added here too (a test fails
// until it is).
inline const std::vector<formula>& formulas() {
  static const std::vector<formula> all{
      DSTRANS_FORMULA(dst_surface, dst_surface_zero).yields(0.0f, 0.0f),
      DSTRANS_FORMULA(dst_light_sample, dst_light_sample_zero).yields(0.0f, 0.0f),
      DSTRANS_FORMULA(dst_alpha_unorm, dst_transparent),
      DSTRANS_FORMULA(dst_alpha_unorm, dst_encode_alpha).within("alpha", {0.0f, 1.0f}).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_alpha_unorm, dst_decode_alpha),
      DSTRANS_FORMULA(dst_normal_unorm, dst_encode_normal).within("n", unit_vector()).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_normal_unorm, dst_decode_normal).within("e", {0.0f, 1.0f}).yields(-1.0f, 1.0f),
      DSTRANS_FORMULA(dst_normal_octahedral_unorm, dst_encode_normal_octahedral).within("n", unit_vector()).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_normal_octahedral_unorm, dst_decode_normal_octahedral).within("e", {0.0f, 1.0f}).yields(-1.0f, 1.0f),
      DSTRANS_FORMULA(dst_white_specular, dst_encode_white_specular).within("s", {0.0f, 1.0f}).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_white_specular, dst_decode_white_specular).within("e", {0.0f, 1.0f}).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_spec_power_unorm, dst_encode_spec_power).within("p", {0.0f, 255.0f}).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_spec_power_unorm, dst_decode_spec_power).within("e", {0.0f, 1.0f}).yields(0.0f, 255.0f),
      DSTRANS_FORMULA(dst_interlace_rows, dst_rows_keep),
      DSTRANS_FORMULA(dst_interlace_rows, dst_rows_partner),
      DSTRANS_FORMULA(dst_interlace_columns, dst_columns_keep),
      DSTRANS_FORMULA(dst_interlace_columns, dst_columns_partner),
      DSTRANS_FORMULA(dst_interlace_checker, dst_checker_keep),
      DSTRANS_FORMULA(dst_interlace_checker, dst_checker_partner),
      DSTRANS_FORMULA(dst_interlace_none, dst_none_keep),
      DSTRANS_FORMULA(dst_interlace_none, dst_none_partner),
      DSTRANS_FORMULA(dst_flip_rows, dst_flip_rows),
      DSTRANS_FORMULA(dst_fullscreen, dst_fullscreen_position).yields(-1.0f, 3.0f),
      DSTRANS_FORMULA(dst_pixel_ndc, dst_pixel_ndc),
      DSTRANS_FORMULA(dst_ndc_window, dst_ndc_window),
      DSTRANS_FORMULA(dst_phong, dst_phong)
          .within({"n", "l", "v"}, unit_vector())
          .within("spec_power", {0.0f, 255.0f})
          .within("light", {0.0f, 4.0f})
          .yields(0.0f, INFINITY),
      DSTRANS_FORMULA(dst_attenuation, dst_attenuation).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_attenuation, dst_spot_falloff).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_light_reach, dst_light_reach)
          .within("direction", unit_vector())
          .within({"position", "p"}, {-100.0f, 100.0f})
          .within("range", {0.0f, 100.0f})
          .within({"cos_outer", "cos_inner"}, {0.0f, 1.0f})
          .yields(-1.0f, 1.0f),
      DSTRANS_FORMULA(dst_transparent_shadow, dst_transparent_shadow)
          .within("light", {0.0f, 4.0f})
          .within({"d_p", "depth_a", "occluder_a", "depth_b", "occluder_b"}, {0.0f, 1.0f})
          .within("bias", {0.0f, 0.01f})
          .yields(0.0f, INFINITY),
      DSTRANS_FORMULA(dst_transparent_shadow, dst_transmitted_shadow)
          .within("light", {0.0f, 4.0f})
          .within({"d_p", "depth_a", "occluder_a", "depth_b", "occluder_b"}, {0.0f, 1.0f})
          .within("bias", {0.0f, 0.01f})
          .yields(0.0f, INFINITY),
      DSTRANS_FORMULA(dst_transparent_shadow, dst_shadowed_light)
          .within("light", {0.0f, 4.0f})
          .within({"d_p", "depth_a", "occluder_a", "depth_b", "occluder_b"}, {0.0f, 1.0f})
          .within("bias", {0.0f, 0.01f})
          .yields(0.0f, INFINITY),
      DSTRANS_FORMULA(dst_transparent_shadow, dst_shadow_texel_transparent),
      DSTRANS_FORMULA(dst_transparent_shadow, dst_shadow_case),
      DSTRANS_FORMULA(dst_transparent_shadow, dst_shadow_alpha),
      DSTRANS_FORMULA(dst_transparent_shadow, dst_shadow_texel_depth),
      DSTRANS_FORMULA(dst_transparent_shadow, dst_nan_to_zero),
      DSTRANS_FORMULA(dst_opaque_shadow, dst_shadow_linear_depth)
          .within("window_depth", {0.0f, 1.0f})
          .within("near_plane", {0.01f, 1.0f})
          .within("far_plane", {2.0f, 100.0f})
          .yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_opaque_shadow, dst_ortho_linear_depth)
          .within("window_depth", {0.0f, 1.0f})
          .within("near_plane", {0.01f, 1.0f})
          .within("far_plane", {2.0f, 100.0f})
          .yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_opaque_shadow, dst_clamp_window_depth).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_shadow_map, dst_map_orthographic),
      DSTRANS_FORMULA(dst_shadow_map, dst_map_cube),
      DSTRANS_FORMULA(dst_shadow_map, dst_map_depth).within("window_depth", {0.0f, 1.0f}).within("map", {1.0f, 3.0f}),
      DSTRANS_FORMULA(dst_shadow_map, dst_map_point_depth).within("clip", {0.5f, 1.0f}).within("map", {1.0f, 3.0f}),
      DSTRANS_FORMULA(dst_shadow_map, dst_map_view_point).within("map", {0.0f, 4.0f}),
      DSTRANS_FORMULA(dst_shadow_map, dst_map_tile_origin).within("map", {0.0f, 4.0f}),
      DSTRANS_FORMULA(dst_shadow_map, dst_map_tile_extent).within("map", {0.0f, 4.0f}),
      DSTRANS_FORMULA(dst_shadow_map, dst_tile_holds),
      DSTRANS_FORMULA(dst_shadow_map, dst_tile_column),
      DSTRANS_FORMULA(dst_shadow_map, dst_map_texel).within("map", {0.0f, 4.0f}),
      DSTRANS_FORMULA(dst_shadow_map, dst_tile_partner),
      DSTRANS_FORMULA(dst_cube_map, dst_cube_face),
      DSTRANS_FORMULA(dst_cube_map, dst_cube_face_view),
      DSTRANS_FORMULA(dst_cube_map, dst_cube_tile_size),
      DSTRANS_FORMULA(dst_cube_map, dst_cube_tile_origin),
      DSTRANS_FORMULA(dst_opaque_shadow, dst_shadow_depth).within({"d_p"}, {0.0f, 2.0f}).within("bias", {0.0f, 0.01f}).yields(-0.01f, 1.0f),
      DSTRANS_FORMULA(dst_opaque_shadow, dst_opaque_shadow)
          .within("light", {0.0f, 4.0f})
          .within({"d_p", "depth"}, {0.0f, 1.0f})
          .within("bias", {0.0f, 0.01f})
          .yields(0.0f, INFINITY),
      DSTRANS_FORMULA(dst_refraction, dst_refraction_offset).within("view_normal", unit_vector()).within("strength", {0.0f, 64.0f}),
      DSTRANS_FORMULA(dst_refraction, dst_refraction_shift).within("offset", {-64.0f, 64.0f}),
      DSTRANS_FORMULA(dst_refraction, dst_refraction_pixel)
          .within("view_normal", unit_vector())
          .within("strength", {0.0f, 64.0f}),
      DSTRANS_FORMULA(dst_refraction, dst_refraction_rejected),
      DSTRANS_FORMULA(dst_refraction, dst_refraction_source)
          .within({"depth_t", "alpha_moved", "depth_moved", "alpha_partner", "depth_partner"}, {0.0f, 1.0f}),
      DSTRANS_FORMULA(dst_refraction, dst_refraction_accepted_by_mask).within({"alpha_moved", "alpha_partner"}, {0.0f, 1.0f}),
      DSTRANS_FORMULA(dst_rough_refraction, dst_phong_power_of_roughness).within("r", {0.0f, 1.0f}).yields(1.0f, 255.0f),
      DSTRANS_FORMULA(dst_rough_refraction, dst_roughness_of_phong_power).within("n", {0.0f, 255.0f}).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_rough_refraction, dst_refraction_blur_pixels)
          .within("roughness", {0.0f, 1.0f})
          .within({"z_t", "z_b"}, {0.1f, 100.0f})
          .within("focal", {0.0f, 2000.0f})
          .within("limit", {0.0f, 64.0f})
          .yields(0.0f, 64.0f),
      DSTRANS_FORMULA(dst_rough_refraction, dst_refraction_blur_tap).yields(-1.0f, 1.0f),
      DSTRANS_FORMULA(dst_compose, dst_shade)
          .within("s", {0.0f, 1.0f})
          .within("l", {0.0f, 4.0f})
          .within("ambient", {0.0f, 1.0f})
          .yields(0.0f, INFINITY),
      DSTRANS_FORMULA(dst_compose, dst_blend)
          .within("opaque", {0.0f, 4.0f})
          .within("transparent", {0.0f, 4.0f})
          .within("alpha_t", {0.0f, 1.0f})
          .yields(0.0f, INFINITY),
      DSTRANS_FORMULA(dst_compose, dst_compose)
          .within({"o", "t", "ambient"}, {0.0f, 1.0f})
          .within({"light_o", "light_t"}, {0.0f, 4.0f})
          .yields(0.0f, INFINITY),
      DSTRANS_FORMULA(dst_light_basis, dst_facing).within({"v", "axis"}, unit_vector()).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_light_basis, dst_six_axis).yields(-1.0f, 1.0f),
      DSTRANS_FORMULA(dst_light_basis, dst_four_axis).yields(-1.0f, 1.0f),
      DSTRANS_FORMULA(dst_light_basis, dst_six_axis_norm).within("l", unit_vector()).yields(1.0f - 1e-6f, 1.7320509f),
      DSTRANS_FORMULA(dst_light_basis, dst_four_axis_norm).within("l", unit_vector()).yields(0.8164965f, 1.1547006f),
      DSTRANS_FORMULA(dst_light_basis, dst_basis_weight)
          .within({"l", "axis"}, unit_vector())
          .within("norm", {1.0f, 2.0f})
          .yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_light_moments, dst_moment_weights).within("l", unit_vector()).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_light_moments, dst_moments_light).within("t", {0.0f, 1.0f}).within("n", unit_vector()).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_volume_texcoord, dst_volume_axis)
          .within({"p", "origin"}, {-4.0f, 4.0f})
          .within({"scale"}, {0.05f, 1.0f})
          .within({"offset"}, {0.0f, 64.0f})
          .within({"dims"}, {1.0f, 32.0f})
          .within({"atlas"}, {64.0f, 128.0f}),
      DSTRANS_FORMULA(dst_volume_texcoord, dst_volume_texcoord)
          .within({"p", "origin"}, {-4.0f, 4.0f})
          .within({"scale"}, {0.05f, 1.0f})
          .within({"offset"}, {0.0f, 64.0f})
          .within({"dims"}, {1.0f, 32.0f})
          .within({"atlas_size"}, {64.0f, 128.0f}),
      DSTRANS_FORMULA(dst_reconstruct, dst_layer_similarity)
          .within({"depth_a", "depth_b"}, {0.0f, 1.0f})
          .within({"normal_a", "normal_b"}, unit_vector())
          .within({"alpha_a", "alpha_b"}, {0.0f, 1.0f})
          .yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_reconstruct, dst_reconstruct).within({"partner", "a", "b", "c"}, {0.0f, 1.0f}).within("weights", {0.0f, 1.0f})
          .yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_history_blend, dst_history_shares).within("offset", {-2.0f, 2.0f}).within("similarity", {0.0f, 1.0f})
          .yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_history_blend, dst_history_box).within({"v", "a", "b"}, {0.0f, 1.0f}).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_history_blend, dst_surface_mix).within({"a", "b", "t"}, {0.0f, 1.0f}).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_history_blend, dst_light_mix).within({"a", "b", "t"}, {0.0f, 1.0f}).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_post, dst_gaussian).within("x", {-16.0f, 16.0f}).within("sigma", {0.1f, 8.0f}).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_post, dst_luminance).within("c", {0.0f, 1.0f}).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_post, dst_bright_pass).within("c", {0.0f, 1.0f}).within("threshold", {0.0f, 1.0f}).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_post, dst_greyscale).within("c", {0.0f, 1.0f}).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_post, dst_at_most_one),
      DSTRANS_FORMULA(dst_post, dst_sepia).within("c", {0.0f, 1.0f}).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_post, dst_blur_amount)
          .within({"distance", "focus"}, {0.0f, 50.0f})
          .within("range", {0.01f, 10.0f})
          .yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_post, dst_edge_weight)
          .within({"n0", "n1"}, unit_vector())
          .within({"d0", "d1"}, {0.1f, 100.0f})
          .within({"normal_scale", "depth_scale"}, {0.0f, 100.0f})
          .yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_octahedral, dst_octahedral_encode).within("n", unit_vector()).yields(-1.0f, 1.0f),
      DSTRANS_FORMULA(dst_octahedral, dst_octahedral_decode).within("e", {-1.0f, 1.0f}).yields(-1.0f, 1.0f),
      DSTRANS_FORMULA(dst_fragment_node, dst_pack_tangent).within("tangent", unit_vector()).packs(16),
      DSTRANS_FORMULA(dst_fragment_node, dst_unpack_tangent).yields(-1.0f, 1.0f),
      DSTRANS_FORMULA(dst_fragment_node, dst_unorm8),
      DSTRANS_FORMULA(dst_fragment_node, dst_pack_colour).within("colour_alpha", {0.0f, 1.0f}),
      DSTRANS_FORMULA(dst_fragment_node, dst_unpack_colour).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_hair, dst_finite3),
      DSTRANS_FORMULA(dst_hair, dst_sine).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_hair, dst_strand_specular)
          .within({"t", "h"}, unit_vector())
          .within("exponent", {1.0f, 128.0f})
          .yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_hair, dst_hair_cheap)
          .within({"t", "l"}, unit_vector())
          .within({"colour", "visibility"}, {0.0f, 1.0f})
          .within("light", {0.0f, 4.0f})
          .yields(0.0f, INFINITY),
      DSTRANS_FORMULA(dst_hair, dst_hair_cheap_mean)
          .within("diag", {0.0f, 1.0f})
          .within("off", {-0.5f, 0.5f})
          .within("l", unit_vector())
          .within({"colour", "visibility"}, {0.0f, 1.0f})
          .within("light", {0.0f, 4.0f})
          .yields(0.0f, INFINITY),
      DSTRANS_FORMULA(dst_hair, dst_hair_full)
          .within({"t", "l", "v"}, unit_vector())
          .within({"colour", "visibility"}, {0.0f, 1.0f})
          .within("light", {0.0f, 4.0f})
          .yields(0.0f, INFINITY),
      DSTRANS_FORMULA(dst_hair, dst_shadow_tap_weight).within({"dx", "dy"}, {-2.0f, 2.0f}).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_hair, dst_hair_transmittance)
          .within({"alpha", "behind"}, {0.0f, 1.0f})
          .within("density", {0.0f, 64.0f})
          .yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_layers, dst_tail_add).within({"tail", "colour_alpha"}, {0.0f, 1.0f}).yields(0.0f, INFINITY),
      DSTRANS_FORMULA(dst_layers, dst_tail_over)
          .within({"background", "tail", "transmittance"}, {0.0f, 1.0f})
          .yields(0.0f, INFINITY),
      DSTRANS_FORMULA(dst_layers, dst_over).within({"behind", "front"}, {0.0f, 1.0f}).yields(0.0f, 1.0f),
      DSTRANS_FORMULA(dst_layers, dst_wboit_weight).within({"alpha", "depth"}, {0.0f, 1.0f}).yields(0.01f, 3000.0f),
      DSTRANS_FORMULA(dst_layers, dst_wboit_resolve)
          .within({"background", "accum", "revealage"}, {0.0f, 1.0f})
          .yields(0.0f, INFINITY),
  };
  return all;
}

// The words of one call's packed arguments.
inline std::size_t argument_words(const formula& f) {
  std::size_t n = 0;
  for (const auto& a : f.args) n += std::size_t(a.second.word_count());
  return n;
}

// The packed results of `calls` calls of `f` on the CPU, whose packed arguments follow each other in
// `args` (the same contract as the backends' GPU runners).
inline words run_cpu(const formula& f, const words& args, std::size_t calls) {
  const std::size_t in_words = argument_words(f);
  words out;
  out.reserve(calls * std::size_t(f.result.word_count()));
  for (std::size_t i = 0; i < calls; ++i) {
    const words one(args.begin() + long(i * in_words), args.begin() + long((i + 1) * in_words));
    const words r = f.cpu(one);
    out.insert(out.end(), r.begin(), r.end());
  }
  return out;
}

// The formula called `name`, or nullptr.
inline const formula* find_formula(const std::string& name) {
  for (const formula& f : formulas())
    if (f.name == name) return &f;
  return nullptr;
}

namespace glsl {

// GLSL statements that unpack a value of type t from the words dst_in[base + at], ... into variable `to`,
// advancing `at`; the shader declares `uint dst_in[]` and `uint base`.
inline void load_value(const value_type& t, const std::string& to, int& at, std::string& code) {
  auto word = [&](int k) { return "dst_in[base + " + std::to_string(at + k) + "u]"; };
  switch (t.kind) {
    case value_kind::record:
      for (const auto& f : t.fields) load_value(f.second, to + "." + f.first, at, code);
      return;
    case value_kind::int_: code += "  " + to + " = int(" + word(0) + ");\n"; break;
    case value_kind::uint_: code += "  " + to + " = " + word(0) + ";\n"; break;
    case value_kind::bool_: code += "  " + to + " = " + word(0) + " != 0u;\n"; break;
    case value_kind::ivec2: code += "  " + to + " = ivec2(int(" + word(0) + "), int(" + word(1) + "));\n"; break;
    default: {
      std::string parts;
      for (int k = 0; k < t.word_count(); ++k) parts += (k ? ", " : "") + ("uintBitsToFloat(" + word(k) + ")");
      code += "  " + to + " = " + t.name() + "(" + parts + ");\n";
    }
  }
  at += t.word_count();
}
// GLSL statements that pack value `from` of type t into dst_out[outbase + at], ..., advancing `at`; the
// shader declares `uint dst_out[]` and `uint outbase`.
inline void store_value(const value_type& t, const std::string& from, int& at, std::string& code) {
  auto word = [&](int k) { return "  dst_out[outbase + " + std::to_string(at + k) + "u] = "; };
  static const char* const comp[] = {".x", ".y", ".z", ".w"};
  switch (t.kind) {
    case value_kind::record:
      for (const auto& f : t.fields) store_value(f.second, from + "." + f.first, at, code);
      return;
    case value_kind::int_: code += word(0) + "uint(" + from + ");\n"; break;
    case value_kind::uint_: code += word(0) + from + ";\n"; break;
    case value_kind::bool_: code += word(0) + from + " ? 1u : 0u;\n"; break;
    case value_kind::ivec2:
      for (int k = 0; k < 2; ++k) code += word(k) + "uint(" + from + comp[k] + ");\n";
      break;
    case value_kind::float_: code += word(0) + "floatBitsToUint(" + from + ");\n"; break;
    default:
      for (int k = 0; k < t.word_count(); ++k) code += word(k) + "floatBitsToUint(" + from + comp[k] + ");\n";
  }
  at += t.word_count();
}

// How many calls of f one dispatch of add_formula_kernel's shader may take on a device whose dispatches
// have at most `max_groups` groups along x and whose storage buffers hold at most `max_buffer_bytes`:
// GPU runners split larger batches into dispatches of this many calls (0: not even one fits).
inline std::size_t calls_per_dispatch(const formula& f, std::size_t max_groups, std::size_t max_buffer_bytes) {
  const std::size_t words = std::max<std::size_t>({argument_words(f), std::size_t(f.result.word_count()), 1});
  const std::size_t by_buffer = max_buffer_bytes / 4 > 1 ? (max_buffer_bytes / 4 - 1) / words : 0;
  return std::min(max_groups * 64, by_buffer);
}

// `calls` calls of f through `dispatch(args, n)` (one GPU dispatch of n calls), split as
// calls_per_dispatch allows: for the GPU runners, which query the two limits from their device.
template <class Dispatch>
result<words> run_in_dispatches(const formula& f, const words& args, std::size_t calls, std::size_t max_groups,
                                std::size_t max_buffer_bytes, Dispatch&& dispatch) {
  const std::size_t chunk = calls_per_dispatch(f, max_groups, max_buffer_bytes);
  if (chunk == 0) return failure{"dstrans eval " + f.name + ": one call does not fit this device's storage buffers"};
  const std::size_t in_words = argument_words(f);
  words out;
  out.reserve(calls * std::size_t(f.result.word_count()));
  for (std::size_t first = 0; first < calls; first += chunk) {
    const std::size_t n = std::min(chunk, calls - first);
    const words part(args.begin() + long(first * in_words), args.begin() + long((first + n) * in_words));
    result<words> r = dispatch(part, n);
    if (!r) return r;
    out.insert(out.end(), r->begin(), r->end());
  }
  return out;
}

// A compute shader (64 invocations a group) that calls formula f once per input. Buffer `in_binding`
// holds the call count in word 0, then each call's packed arguments; buffer `out_binding` receives each
// call's packed result.
inline void add_formula_kernel(source& src, const formula& f, int in_binding = 0, int out_binding = 1) {
  src.add_shared(*f.block);
  int in_words = 0, out_words = f.result.word_count();
  for (const auto& a : f.args) in_words += a.second.word_count();
  std::string code = "layout(local_size_x = 64) in;\n";
  code += "layout(std430, binding = " + std::to_string(in_binding) + ") readonly buffer dst_eval_in { uint dst_in[]; };\n";
  code += "layout(std430, binding = " + std::to_string(out_binding) + ") writeonly buffer dst_eval_out { uint dst_out[]; };\n";
  code += "void main() {\n  uint i = gl_GlobalInvocationID.x;\n  if (i >= dst_in[0]) return;\n";
  code += "  uint base = 1u + i * " + std::to_string(in_words) + "u;\n";
  code += "  uint outbase = i * " + std::to_string(out_words) + "u;\n";
  int at = 0;
  std::string call;
  for (std::size_t k = 0; k < f.args.size(); ++k) {
    const std::string a = "a" + std::to_string(k);
    code += "  " + f.args[k].second.name() + " " + a + ";\n";
    load_value(f.args[k].second, a, at, code);
    call += (k ? ", " : "") + a;
  }
  code += "  " + f.result.name() + " r = " + f.name + "(" + call + ");\n";
  at = 0;
  store_value(f.result, "r", at, code);
  code += "}\n";
  src.add(code, __FILE__, __LINE__);
}

}  // namespace glsl
}  // namespace dstrans

// Render-target layouts: which named fields live in which channels of which targets, described once as
// a type and turned into GLSL (outputs, samplers, pack/unpack, hooks) and into the matching CPU code.
//
//   using my_gbuffer = dstrans::layout<dstrans::surface,
//       dstrans::target<dstrans::format::rgba8, dstrans::field::diffuse, dstrans::field::alpha>,
//       dstrans::target<dstrans::format::rgba16f, dstrans::field::normal, dstrans::field::depth>>;
//   static_assert(my_gbuffer::bytes_per_pixel == 12);
//   auto bytes = dstrans::write<my_gbuffer>(s);          // what the GPU stores for surface s
//   dstrans::surface back = dstrans::read<my_gbuffer>(bytes);
//   dstrans::glsl::source src;
//   dstrans::glsl::add_layout<my_gbuffer>(src, "gbuffer");   // dst_gbuffer_write(s), dst_gbuffer_read(p)
//
// A layout that cannot work does not compile, with a sentence that says why.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "format.hpp"
#include "glsl.hpp"
#include "surface.hpp"

namespace dstrans {

// How a field of type T is squeezed into UNORM channels, as shared code.
template <class T>
struct codec {
  const shared_text* text;  // the shared block that defines both functions
  const char* encode_name;
  const char* decode_name;
  T (*encode)(T);
  T (*decode)(T);
};

#define DSTRANS_CODEC(T, block, enc, dec) \
  ::dstrans::codec<T> { &::dstrans::text::block, #enc, #dec, &::dstrans::shader::enc, &::dstrans::shader::dec }

inline constexpr codec<glm::vec3> normal_unorm = DSTRANS_CODEC(glm::vec3, dst_normal_unorm, dst_encode_normal, dst_decode_normal);
// Two channels for a vec3: the CPU side is the field's own (field::normal_octahedral), so no function
// pointers here.
inline constexpr codec<glm::vec3> normal_octahedral_unorm{&text::dst_normal_octahedral_unorm, "dst_encode_normal_octahedral",
                                                          "dst_decode_normal_octahedral", nullptr, nullptr};
inline constexpr codec<float> alpha_unorm = DSTRANS_CODEC(float, dst_alpha_unorm, dst_encode_alpha, dst_decode_alpha);
// One channel for a vec3 in any format: the CPU side is the field's own (field::specular).
inline constexpr codec<glm::vec3> white_specular{&text::dst_white_specular, "dst_encode_white_specular",
                                                 "dst_decode_white_specular", nullptr, nullptr};
inline constexpr codec<float> spec_power_unorm =
    DSTRANS_CODEC(float, dst_spec_power_unorm, dst_encode_spec_power, dst_decode_spec_power);

namespace detail {

template <class T>
constexpr int components() {
  if constexpr (std::is_same_v<T, float>) return 1;
  else return int(T::length());
}

// Whether field F's codec applies in a target of kind `kind`: in UNORM channels, and wherever F keeps its
// value in fewer channels than the value has (the codec is then the only way in and out).
template <class F>
constexpr bool encodes(channel_kind kind) {
  if constexpr (std::is_same_v<typename F::record, void>) return false;
  else return F::unorm && (kind == channel_kind::unorm || F::channels != components<typename F::value_type>());
}

constexpr bool same_name(const char* a, const char* b) {
  while (*a && *a == *b) ++a, ++b;
  return *a == *b;
}

// A field: a member of a record, its GLSL name, the bits a channel needs to keep it useful, and its
// UNORM codec (nullptr: stored as is, which needs values in [0, 1]).
template <class Record, class T, T Record::*Member, int MinBits, const codec<T>* Unorm = nullptr>
struct field_base {
  using record = Record;
  using value_type = T;
  static constexpr int channels = components<T>();
  static constexpr int min_bits = MinBits;
  static constexpr const codec<T>* unorm = Unorm;

  static void store(const Record& r, glm::vec4& v, int offset, channel_kind kind) {
    T x = r.*Member;
    if (Unorm && kind == channel_kind::unorm) x = Unorm->encode(x);
    if constexpr (channels == 1) v[offset] = x;
    else for (int i = 0; i < channels; ++i) v[offset + i] = x[i];
  }
  static void load(const glm::vec4& v, int offset, channel_kind kind, Record& r) {
    T x;
    if constexpr (channels == 1) x = v[offset];
    else for (int i = 0; i < channels; ++i) x[i] = v[offset + i];
    if (Unorm && kind == channel_kind::unorm) x = Unorm->decode(x);
    r.*Member = x;
  }
};

// A field that keeps a vec3 in fewer channels through `Codec`; the field itself stores and loads it on the CPU.
template <class Record, int Channels, const codec<glm::vec3>* Codec>
struct narrowed_field {
  using record = Record;
  using value_type = glm::vec3;
  static constexpr int channels = Channels;
  static constexpr int min_bits = 8;
  static constexpr const codec<glm::vec3>* unorm = Codec;
};

}  // namespace detail

// The fields dstrans knows; a layout stores each at most once.
namespace field {
struct diffuse : detail::field_base<surface, glm::vec3, &surface::diffuse, 8> {
  static constexpr const char* name = "diffuse";
  static constexpr const char* parts = "rgb";
};
struct alpha : detail::field_base<surface, float, &surface::alpha, 8, &alpha_unorm> {
  static constexpr const char* name = "alpha";
  static constexpr const char* parts = "";
};
struct normal : detail::field_base<surface, glm::vec3, &surface::normal, 8, &normal_unorm> {
  static constexpr const char* name = "normal";
  static constexpr const char* parts = "xyz";
};
// The normal in two channels, octahedrally (the compact layout), through its codec in every target.
struct normal_octahedral : detail::narrowed_field<surface, 2, &normal_octahedral_unorm> {
  static constexpr const char* name = "normal";
  static constexpr const char* parts = "uv";
  static void store(const surface& r, glm::vec4& v, int offset, channel_kind) {
    const glm::vec2 e = shader::dst_encode_normal_octahedral(r.normal);
    v[offset] = e.x;
    v[offset + 1] = e.y;
  }
  static void load(const glm::vec4& v, int offset, channel_kind, surface& r) {
    r.normal = shader::dst_decode_normal_octahedral(glm::vec2(v[offset], v[offset + 1]));
  }
};
struct spec_intensity : detail::field_base<surface, float, &surface::spec_intensity, 8> {
  static constexpr const char* name = "spec_intensity";
  static constexpr const char* parts = "";
};
struct spec_power : detail::field_base<surface, float, &surface::spec_power, 8, &spec_power_unorm> {
  static constexpr const char* name = "spec_power";
  static constexpr const char* parts = "";
};
struct depth : detail::field_base<surface, float, &surface::depth, 24> {
  static constexpr const char* name = "depth";
  static constexpr const char* parts = "";
};
struct light : detail::field_base<light_sample, glm::vec3, &light_sample::light, 8> {
  static constexpr const char* name = "light";
  static constexpr const char* parts = "rgb";
};
// The thesis's white specular: one channel, the mean of the three (dst_encode_white_specular).
struct specular : detail::narrowed_field<light_sample, 1, &white_specular> {
  static constexpr const char* name = "specular";
  static constexpr const char* parts = "";
  static void store(const light_sample& r, glm::vec4& v, int offset, channel_kind) {
    v[offset] = shader::dst_encode_white_specular(r.specular);
  }
  static void load(const glm::vec4& v, int offset, channel_kind, light_sample& r) {
    r.specular = shader::dst_decode_white_specular(v[offset]);
  }
};
// The specular response in three channels, coloured as the light is.
struct specular_rgb : detail::field_base<light_sample, glm::vec3, &light_sample::specular, 8> {
  static constexpr const char* name = "specular";
  static constexpr const char* parts = "rgb";
};
}  // namespace field

// N channels a layout leaves unused (written as 0).
template <int N>
struct unused {
  using record = void;
  static constexpr int channels = N;
  static constexpr int min_bits = 0;
  static constexpr const char* name = nullptr;
  static constexpr const char* parts = "";
  template <class Record>
  static void store(const Record&, glm::vec4&, int, channel_kind) {}
  template <class Record>
  static void load(const glm::vec4&, int, channel_kind, Record&) {}
};

namespace detail {
template <format F, class... Fields>
constexpr bool fields_have_bits() {
  int offset = 0;
  bool ok = true;
  ((ok = ok && [&] {
     for (int c = offset; c < offset + Fields::channels && c < info(F).channels; ++c)
       if (info(F).bits[std::size_t(c)] < Fields::min_bits) return false;
     return true;
   }(),
    offset += Fields::channels),
   ...);
  return ok;
}
}  // namespace detail

// One render target: a format and the fields in its channels, in channel order.
template <format F, class... Fields>
struct target {
  static constexpr format fmt = F;
  static constexpr int channels_used = (0 + ... + Fields::channels);
  static_assert(channels_used <= info(F).channels,
                "dstrans layout: the fields of a target need more channels than its format has.");
  static_assert(detail::fields_have_bits<F, Fields...>(),
                "dstrans layout: a field sits in a channel with too few bits to keep it (alpha, diffuse, "
                "normal and specular need 8 bits, depth needs 24; an RGB10A2 alpha has 2).");

  template <class Record>
  static glm::vec4 pack(const Record& r) {
    glm::vec4 v(0.0f);
    int offset = 0;
    ((Fields::store(r, v, offset, info(F).kind), offset += Fields::channels), ...);
    return v;
  }
  template <class Record>
  static void unpack(const glm::vec4& v, Record& r) {
    int offset = 0;
    ((Fields::load(v, offset, info(F).kind, r), offset += Fields::channels), ...);
  }
  template <class Visit>
  static void each_field(Visit&& visit) {
    int offset = 0;
    ((visit(Fields{}, offset), offset += Fields::channels), ...);
  }
};

namespace detail {
template <class Record, class Field>
constexpr bool belongs() {
  return std::is_same_v<typename Field::record, void> || std::is_same_v<typename Field::record, Record>;
}
}  // namespace detail

// A set of render targets written together, storing one Record (dstrans::surface or
// dstrans::light_sample) a pixel.
template <class Record, class... Targets>
struct layout {
  using record = Record;
  static constexpr int target_count = int(sizeof...(Targets));
  static constexpr int bytes_per_pixel = (0 + ... + info(Targets::fmt).bytes_per_pixel);
  static constexpr std::array<format, sizeof...(Targets)> formats{Targets::fmt...};

  static_assert(target_count >= 1, "dstrans layout: a layout needs at least one render target.");
  static_assert(target_count <= 8,
                "dstrans layout: more than 8 render targets; OpenGL 4.5 and Vulkan only promise 8 "
                "(GL_MAX_DRAW_BUFFERS, maxColorAttachments).");

  // Whether the layout stores the record member that Field carries.
  template <class Field>
  static constexpr bool stores() {
    return count(Field::name) > 0;
  }

  template <class Visit>
  static void each_target(Visit&& visit) {
    int i = 0;
    ((visit(Targets{}, i++)), ...);
  }

 private:
  template <class Target>
  struct field_names;
  template <format F, class... Fields>
  struct field_names<target<F, Fields...>> {
    static constexpr int count(const char* name) {
      return (0 + ... + (Fields::name && detail::same_name(Fields::name, name) ? 1 : 0));
    }
    static constexpr bool records_match() { return (true && ... && detail::belongs<Record, Fields>()); }
    static constexpr bool unique() {
      return (true && ... && (!Fields::name || layout::count(Fields::name) == 1));
    }
  };
  static constexpr int count(const char* name) { return (0 + ... + field_names<Targets>::count(name)); }

  static_assert((true && ... && field_names<Targets>::records_match()),
                "dstrans layout: a field belongs to another record (a G-buffer stores dstrans::surface "
                "fields, a light buffer dstrans::light_sample fields).");
  static_assert((true && ... && field_names<Targets>::unique()),
                "dstrans layout: a field is stored twice; each field may live in one place only.");
};

// Compiles only if layout L stores every field a technique reads.
template <class L, class... Fields>
constexpr bool requires_fields() {
  static_assert((L::template stores<Fields>() && ...),
                "dstrans layout: a technique reads a field that this layout does not store (the field "
                "types are in the instantiation above).");
  return true;
}

// The channel values a shader writes for record `r`, one vec4 a target, before the target quantises them.
template <class L>
std::array<glm::vec4, L::target_count> pack(const typename L::record& r) {
  std::array<glm::vec4, L::target_count> out{};
  L::each_target([&](auto t, int i) { out[std::size_t(i)] = decltype(t)::pack(r); });
  return out;
}

// The record a shader reads from channel values `v` (fields the layout lacks stay 0).
template <class L>
typename L::record unpack(const std::array<glm::vec4, L::target_count>& v) {
  typename L::record r{};
  L::each_target([&](auto t, int i) { decltype(t)::unpack(v[std::size_t(i)], r); });
  return r;
}

// The bytes the GPU stores in each target when a shader writes `r`.
template <class L>
std::array<texel, L::target_count> write(const typename L::record& r) {
  const auto v = pack<L>(r);
  std::array<texel, L::target_count> out{};
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = encode(L::formats[i], v[i]);
  return out;
}

// The record a shader reads from the targets' bytes `t`.
template <class L>
typename L::record read(const std::array<texel, L::target_count>& t) {
  std::array<glm::vec4, L::target_count> v{};
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = decode(L::formats[i], t[i]);
  return unpack<L>(v);
}

// One target as data: its format and what each stored channel holds ("normal.x", "unused").
struct target_desc {
  format fmt;
  std::vector<std::string> channels;
};

// Layout L as data, for tools, backends and reports.
template <class L>
std::vector<target_desc> describe() {
  std::vector<target_desc> out;
  L::each_target([&](auto t, int) {
    using T = decltype(t);
    target_desc d{T::fmt, {}};
    T::each_field([&](auto f, int) {
      using F = decltype(f);
      for (int c = 0; c < F::channels; ++c) {
        if (!F::name) d.channels.push_back("unused");
        else if (F::channels == 1) d.channels.push_back(F::name);
        else d.channels.push_back(std::string(F::name) + "." + F::parts[c]);
      }
    });
    out.push_back(d);
  });
  return out;
}

namespace glsl {

// Which halves of a layout's GLSL to emit. pack/unpack are always emitted.
enum class side { write, read, both };

struct layout_options {
  side sides = side::both;
  int first_location = 0;  // the output location of target 0
  int first_binding = 0;   // the sampler binding of target 0 (where the source's version has bindings)
  // For a layout without a depth field (compact_gbuffer): the binding of the depth attachment the read
  // side takes depth from (-1: none, depth reads 0).
  int depth_attachment_binding = -1;
};

namespace detail {
inline const char* swizzle(int offset, int n) {
  static const char* const table[4][4] = {{"x", "xy", "xyz", "xyzw"}, {"y", "yz", "yzw", ""}, {"z", "zw", "", ""}, {"w", "", "", ""}};
  return table[offset][n - 1];
}
inline const char* vec_type(int n) { return n == 1 ? "float" : n == 2 ? "vec2" : n == 3 ? "vec3" : "vec4"; }
// A sampler's layout qualifier at `binding`, where `src`'s version has one (else the engine binds it by name).
inline std::string sampler_binding(const source& src, int binding) {
  return src.binds() ? "layout(binding = " + std::to_string(binding) + ") " : "";
}
template <class Record>
const shared_text& record_text();
template <>
inline const shared_text& record_text<surface>() { return text::dst_surface; }
template <>
inline const shared_text& record_text<light_sample>() { return text::dst_light_sample; }
inline std::string upper(std::string s) {
  for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
  return s;
}
}  // namespace detail

// A comment that tabulates layout L the way the thesis's Tables 3.1-3.3 do.
template <class L>
std::string layout_table(const std::string& name) {
  std::string s = "// dstrans layout \"" + name + "\": " + std::to_string(L::target_count) + " render target" +
                  (L::target_count == 1 ? "" : "s") + ", " + std::to_string(L::bytes_per_pixel) +
                  " bytes a pixel\n";
  int i = 0;
  for (const target_desc& t : describe<L>()) {
    std::string row = "//   RT" + std::to_string(i++) + "  " + info(t.fmt).name;
    row.append(row.size() < 18 ? 18 - row.size() : 1, ' ');
    for (std::size_t c = 0; c < t.channels.size(); ++c) {
      std::string cell = t.channels[c] + "(" + std::to_string(info(t.fmt).bits[c]) + ")";
      row += cell;
      if (c + 1 < t.channels.size()) row.append(cell.size() < 18 ? 18 - cell.size() : 1, ' ');
    }
    s += row + "\n";
  }
  return s;
}

// Appends layout L's GLSL under `name`: record struct and codecs (shared code), then
//   void dst_NAME_pack(RECORD r, out vec4 t0, ...);   RECORD dst_NAME_unpack(vec4 t0, ...);
// and, as opt.sides asks,
//   write side: outputs at opt.first_location..., void dst_NAME_store(int target, vec4 v), void dst_NAME_write(RECORD r)
//   read side:  samplers dst_NAME_tex0... at opt.first_binding... (before GLSL 4.20: by name alone),
//               vec4 dst_NAME_fetch(int target, ivec2 pixel), RECORD dst_NAME_read(ivec2 pixel)
//               (with opt.depth_attachment_binding, a layout without depth reads it from that sampler)
// An engine with its own bindings defines DSTRANS_NAME_STORE or DSTRANS_NAME_FETCH (NAME in capitals)
// before this code and implements dst_NAME_store or dst_NAME_fetch itself.
template <class L>
void add_layout(source& src, const std::string& name, const layout_options& opt = {}) {
  using Record = typename L::record;
  const shared_text& rec = detail::record_text<Record>();
  src.add_shared(rec);
  L::each_target([&](auto t, int) {
    using T = decltype(t);
    T::each_field([&](auto f, int) {
      using F = decltype(f);
      if constexpr (!std::is_same_v<typename F::record, void>)
        if (dstrans::detail::encodes<F>(info(T::fmt).kind)) src.add_shared(*F::unorm->text);
    });
  });
  const std::string fn = "dst_" + name, macro = "DSTRANS_" + detail::upper(name), rtype = rec.name;
  const int n = L::target_count;
  std::string out_params, in_params, args, code = layout_table<L>(name);
  for (int i = 0; i < n; ++i) {
    const std::string sep = i ? ", " : "", t = "t" + std::to_string(i);
    out_params += sep + "out vec4 " + t;
    in_params += sep + "vec4 " + t;
    args += sep + t;
  }
  code += "void " + fn + "_pack(" + rtype + " r, " + out_params + ") {\n";
  L::each_target([&](auto t, int i) {
    using T = decltype(t);
    std::string parts;
    T::each_field([&](auto f, int) {
      using F = decltype(f);
      std::string e;
      if constexpr (std::is_same_v<typename F::record, void>) {
        for (int c = 0; c < F::channels; ++c) e += std::string(c ? ", " : "") + "0.0f";
      } else {
        e = std::string("r.") + F::name;
        if (dstrans::detail::encodes<F>(info(T::fmt).kind)) e = std::string(F::unorm->encode_name) + "(" + e + ")";
      }
      parts += (parts.empty() ? "" : ", ") + e;
    });
    for (int c = T::channels_used; c < 4; ++c) parts += (parts.empty() ? "" : ", ") + std::string("0.0f");
    code += "  t" + std::to_string(i) + " = vec4(" + parts + ");\n";
  });
  code += "}\n\n" + rtype + " " + fn + "_unpack(" + in_params + ") {\n";
  code += "  " + rtype + " r = " + rtype + "_zero();\n";
  L::each_target([&](auto t, int i) {
    using T = decltype(t);
    T::each_field([&](auto f, int offset) {
      using F = decltype(f);
      if constexpr (!std::is_same_v<typename F::record, void>) {
        std::string e = "t" + std::to_string(i) + "." + detail::swizzle(offset, F::channels);
        if (dstrans::detail::encodes<F>(info(T::fmt).kind)) e = std::string(F::unorm->decode_name) + "(" + e + ")";
        code += std::string("  r.") + F::name + " = " + e + ";\n";
      }
    });
  });
  code += "  return r;\n}\n";

  if (opt.sides != side::read) {
    code += "\n#ifndef " + macro + "_STORE\n";
    L::each_target([&](auto t, int i) {
      const int ch = info(decltype(t)::fmt).channels;
      code += "layout(location = " + std::to_string(opt.first_location + i) + ") out " + detail::vec_type(ch) + " " +
              fn + "_rt" + std::to_string(i) + ";\n";
    });
    code += "void " + fn + "_store(int target, vec4 v) {\n";
    L::each_target([&](auto t, int i) {
      const int ch = info(decltype(t)::fmt).channels;
      code += "  if (target == " + std::to_string(i) + ") " + fn + "_rt" + std::to_string(i) + " = " +
              (ch == 4 ? std::string("v") : std::string("v.") + detail::swizzle(0, ch)) + ";\n";
    });
    code += "}\n#endif\n";
    code += "void " + fn + "_write(" + rtype + " r) {\n  vec4 " + args + ";\n  " + fn + "_pack(r, " + args + ");\n";
    for (int i = 0; i < n; ++i) code += "  " + fn + "_store(" + std::to_string(i) + ", t" + std::to_string(i) + ");\n";
    code += "}\n";
  }
  if (opt.sides != side::write) {
    code += "\n#ifndef " + macro + "_FETCH\n";
    for (int i = 0; i < n; ++i)
      code += detail::sampler_binding(src, opt.first_binding + i) + "uniform sampler2D " + fn + "_tex" + std::to_string(i) + ";\n";
    code += "vec4 " + fn + "_fetch(int target, ivec2 pixel) {\n";
    for (int i = 0; i + 1 < n; ++i)
      code += "  if (target == " + std::to_string(i) + ") return texelFetch(" + fn + "_tex" + std::to_string(i) +
              ", pixel, 0);\n";
    code += "  return texelFetch(" + fn + "_tex" + std::to_string(n - 1) + ", pixel, 0);\n}\n#endif\n";
    const bool attachment = opt.depth_attachment_binding >= 0 && !L::template stores<field::depth>();
    if (attachment)
      code += detail::sampler_binding(src, opt.depth_attachment_binding) + "uniform sampler2D " + fn + "_depth_attachment;\n";
    code += rtype + " " + fn + "_read(ivec2 pixel) {\n  " + rtype + " r = " + fn + "_unpack(";
    for (int i = 0; i < n; ++i) code += std::string(i ? ", " : "") + fn + "_fetch(" + std::to_string(i) + ", pixel)";
    code += ");\n";
    if (attachment) code += "  r.depth = texelFetch(" + fn + "_depth_attachment, pixel, 0).r;\n";
    code += "  return r;\n}\n";
  }
  src.add(code, __FILE__, __LINE__);
}

}  // namespace glsl
}  // namespace dstrans

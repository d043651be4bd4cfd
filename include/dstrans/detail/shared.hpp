// One formula, one text.
//
// A shared block is written once, in the subset of GLSL that GLM-based C++17 also accepts, inside
// DSTRANS_SHARED(name, code...). The C++ compiler compiles the code into namespace dstrans::shader;
// the preprocessor also keeps the very same tokens as text (dstrans::text::name), which the GLSL
// generators emit. The CPU reference and the shader therefore cannot drift apart.
//
//   DSTRANS_SHARED(dst_half,
//   DST_FN float dst_half(float x) { return x * 0.5f; }
//   )
//   float a = dstrans::shader::dst_half(3.0f);        // C++
//   std::string glsl = dstrans::text::dst_half.code;   // GLSL
//
// Rules for shared code, because it must mean the same in both languages:
// - float literals carry an `f` suffix (GLM does not mix float and double);
// - no swizzles (`v.xy`): write `vec2(v.x, v.y)`; member access `.x .y .z .w` is fine;
// - no preprocessor directives and no struct constructors (C++17 has no parenthesised aggregate
//   init): build a struct member by member;
// - out and inout parameters are DST_OUT(T) and DST_INOUT(T); every function is DST_FN;
// - integer arithmetic on non-negative values only (`%` and `>>` of negatives differ), and no signed
//   overflow (undefined in C++);
// - where a NaN can arrive, decide it with isnan() before any comparison, min, max, clamp or smoothstep:
//   GLSL leaves them undefined for NaN, GPUs and GLM answer differently, and Mesa's GL compiler folds
//   `!(x > 0.0f)` followed by a select into code that keeps the NaN (measured: dst_attenuation).
// The stringified text loses comments and line breaks; dstrans::glsl re-breaks it for reading and
// maps compiler errors back to the line of the DSTRANS_SHARED block.
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace dstrans {

// The text of one shared block and where it was written.
struct shared_text {
  const char* name;  // the block's name, which is also its main function or struct
  const char* code;  // the block's code as the C++ compiler saw it, before macro expansion
  const char* file;  // the header that holds it
  int line;          // the line of its DSTRANS_SHARED
};

// Shared code sees GLM as GLSL sees its built-ins (vec3, dot, uint, ...). Each is declared here by name,
// not through `using namespace glm`: that would put them beside an includer's `using namespace std` (or
// its own min, max and clamp) in the global namespace, and an unqualified max(float, float) would be
// ambiguous. Declared here, they are found first.
namespace shader {
using glm::bvec2, glm::bvec3, glm::bvec4, glm::ivec2, glm::ivec3, glm::ivec4, glm::mat2, glm::mat3, glm::mat4, glm::uint,
    glm::uvec2, glm::uvec3, glm::uvec4, glm::vec2, glm::vec3, glm::vec4;
using glm::abs, glm::acos, glm::asin, glm::atan, glm::ceil, glm::clamp, glm::cos, glm::cross, glm::degrees, glm::distance,
    glm::dot, glm::exp, glm::exp2, glm::faceforward, glm::floatBitsToInt, glm::floatBitsToUint, glm::floor, glm::fract,
    glm::intBitsToFloat, glm::inverse, glm::inversesqrt, glm::isinf, glm::isnan, glm::length, glm::log, glm::log2,
    glm::max, glm::min, glm::mix, glm::mod, glm::normalize, glm::pow, glm::radians, glm::reflect, glm::refract,
    glm::round, glm::sign, glm::sin, glm::smoothstep, glm::sqrt, glm::step, glm::tan, glm::transpose, glm::trunc,
    glm::uintBitsToFloat;
using glm::packHalf2x16, glm::packSnorm2x16, glm::packSnorm4x8, glm::packUnorm2x16, glm::packUnorm4x8, glm::unpackHalf2x16,
    glm::unpackSnorm2x16, glm::unpackSnorm4x8, glm::unpackUnorm2x16, glm::unpackUnorm4x8;
}  // namespace shader

}  // namespace dstrans

// The GLSL definitions of the shared-code keywords; emitted once before any shared block.
#define DSTRANS_GLSL_KEYWORDS \
  "#define DST_FN\n#define DST_OUT(T) out T\n#define DST_INOUT(T) inout T\n"

#define DST_FN inline
#define DST_OUT(T) T&
#define DST_INOUT(T) T&

namespace dstrans::detail {
// Every shared block in the program, in no particular order: tests use it to find formulas that are not
// reachable through dstrans eval.
inline std::vector<const shared_text*>& shared_blocks() {
  static std::vector<const shared_text*> blocks;
  return blocks;
}
struct shared_block_registration {
  explicit shared_block_registration(const shared_text* t) { shared_blocks().push_back(t); }
};
}  // namespace dstrans::detail

// Parameters that a formula ignores on some inputs are still named, as GLSL wants; hence the pragma.
#define DSTRANS_SHARED(ident, ...)                                                        \
  _Pragma("GCC diagnostic push") _Pragma("GCC diagnostic ignored \"-Wunused-parameter\"") \
  namespace dstrans::shader { __VA_ARGS__ }                                               \
  _Pragma("GCC diagnostic pop")                                                           \
  namespace dstrans::text {                                                               \
  inline constexpr ::dstrans::shared_text ident{#ident, #__VA_ARGS__, __FILE__, __LINE__}; \
  inline const ::dstrans::detail::shared_block_registration ident##_registration{&ident};  \
  }

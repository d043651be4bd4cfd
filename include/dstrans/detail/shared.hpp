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

// Shared code sees GLM as GLSL sees its built-ins (vec3, dot, uint, ...).
namespace shader {
using namespace glm;
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

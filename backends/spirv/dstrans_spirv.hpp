// GLSL to SPIR-V (glslang) and SPIR-V reflection (SPIRV-Cross), for the Vulkan backend and for checking
// generated code. Copy dstrans_spirv.{hpp,cpp} into an engine unmodified; link glslang, its SPIRV and
// default-resource-limits libraries, and spirv-cross-core.
//
//   auto words = dstrans::spirv::compile(src, dstrans::spirv::stage::fragment, dstrans::spirv::api::vulkan);
//   if (!words) std::fprintf(stderr, "%s\n", words.error().c_str());   // "include/dstrans/x.hpp:40: error: ..."
//   auto refl = dstrans::spirv::reflect(*words);                         // outputs, samplers, buffers
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <dstrans/glsl.hpp>
#include <dstrans/result.hpp>

namespace dstrans::spirv {

enum class api { opengl, vulkan };
enum class stage { vertex, fragment, compute };

// `src` compiled to SPIR-V for `target` (OpenGL 4.5 / SPIR-V 1.0, or Vulkan 1.2 / SPIR-V 1.5); on failure
// the compiler's log with every position mapped to the dstrans source it came from.
result<std::vector<std::uint32_t>> compile(const glsl::source& src, stage st, api target);

// A stage input or output.
struct interface_variable {
  int location;
  std::string name;
  int components;  // 1 for float, 4 for vec4
};

// A descriptor-bound resource.
struct resource {
  int set;
  int binding;
  std::string name;
};

// What a SPIR-V module declares, sorted by location or (set, binding).
struct reflection {
  std::vector<interface_variable> inputs, outputs;
  std::vector<resource> samplers, uniform_buffers, storage_buffers, storage_images;
  std::vector<resource> texel_buffers;  // samplerBuffer: Vulkan's uniform texel buffers (not in samplers)
};

// The interface of SPIR-V module `words`; a failure if it cannot be parsed.
result<reflection> reflect(const std::vector<std::uint32_t>& words);

}  // namespace dstrans::spirv

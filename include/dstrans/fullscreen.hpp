// The full-screen triangle every screen-space pass draws: three vertices, no vertex buffer.
//
//   dstrans::glsl::source vs = dstrans::glsl::fullscreen_vertex_shader();   // draw 3 vertices
//   glm::vec2 clip = dstrans::shader::dst_fullscreen_position(2);           // (-1, 3)
#pragma once

#include "detail/shared.hpp"
#include "glsl.hpp"

// Clip-space position of vertex 0, 1 or 2 of a triangle that covers [-1, 1]^2: (-1,-1), (3,-1), (-1,3).
DSTRANS_SHARED(dst_fullscreen,
DST_FN vec2 dst_fullscreen_position(int vertex) {
  return vec2(float((vertex & 1) * 4 - 1), float((vertex & 2) * 2 - 1));
}
)

namespace dstrans::glsl {

// A vertex shader that places the full-screen triangle from gl_VertexIndex (Vulkan) or gl_VertexID (GL).
inline source fullscreen_vertex_shader() {
  source src;
  src.add_shared(text::dst_fullscreen);
  src.add(
      "#ifdef VULKAN\n#define DST_VERTEX_INDEX gl_VertexIndex\n#else\n#define DST_VERTEX_INDEX gl_VertexID\n#endif\n"
      "void main() { gl_Position = vec4(dst_fullscreen_position(DST_VERTEX_INDEX), 0.0f, 1.0f); }\n",
      __FILE__, __LINE__);
  return src;
}

}  // namespace dstrans::glsl

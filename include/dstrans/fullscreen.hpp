// Screen-space conventions: the full-screen triangle every screen-space pass draws (three vertices, no
// vertex buffer), and where a pixel's centre lies in normalized device coordinates.
//
//   dstrans::glsl::source vs = dstrans::glsl::fullscreen_vertex_shader();   // draw 3 vertices
//   glm::vec2 clip = dstrans::shader::dst_fullscreen_position(2);           // (-1, 3)
//   glm::vec2 ndc = dstrans::shader::dst_pixel_ndc({0, 0}, {4, 2});          // (-0.75, 0.5): top left
//   glm::vec2 at = dstrans::shader::dst_ndc_window(ndc, {4, 2});            // (0.5, 0.5): its centre
#pragma once

#include "detail/shared.hpp"
#include "glsl.hpp"

// Clip-space position of vertex 0, 1 or 2 of a triangle that covers [-1, 1]^2: (-1,-1), (3,-1), (-1,3).
DSTRANS_SHARED(dst_fullscreen,
DST_FN vec2 dst_fullscreen_position(int vertex) {
  return vec2(float((vertex & 1) * 4 - 1), float((vertex & 2) * 2 - 1));
}
)

// The centre of `pixel` (column from the left, row from the top) in the normalized device coordinates of
// an image of `size` (clip-space +y is the top row on both backends); sizes below 1 count as 1.
DSTRANS_SHARED(dst_pixel_ndc,
DST_FN vec2 dst_pixel_ndc(ivec2 pixel, ivec2 size) {
  vec2 extent = vec2(max(size, ivec2(1)));
  return vec2((float(pixel.x) + 0.5f) / extent.x * 2.0f - 1.0f, 1.0f - (float(pixel.y) + 0.5f) / extent.y * 2.0f);
}
)

// The window position (pixels from the top left, continuous: pixel (x, y) spans [x, x + 1) x [y, y + 1)) of
// normalized device coordinates `ndc` in an image of `size`: dst_pixel_ndc's inverse.
DSTRANS_SHARED(dst_ndc_window,
DST_FN vec2 dst_ndc_window(vec2 ndc, ivec2 size) {
  return vec2(ndc.x * 0.5f + 0.5f, 0.5f - ndc.y * 0.5f) * vec2(size);
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

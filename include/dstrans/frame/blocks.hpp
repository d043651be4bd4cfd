// The blocks every pass of the reference pipeline reads, written once for C++ and GLSL (DSTRANS_SHARED):
// the frame (std140), each material (three RGBA32F texels of a texel buffer) and each light (std430). The
// pass shader frame.glsl declares them at the slots of frame/slots.hpp; a pass that names one gets its
// definition with it.
//
//   dstrans::shader::dst_light_data light{};          // C++: fill it and upload it as it is
//   light.position_range = glm::vec4(position, range);
//   // GLSL: layout(std430, binding = DST_SLOT_LIGHTS) readonly buffer dst_lights { dst_light_data lights[]; };
//
// Every member is a vec4, ivec4 or mat4, so std140, std430 and C++ lay them out alike.
#pragma once

#include "../detail/shared.hpp"

DSTRANS_SHARED(dst_frame_data,
struct dst_frame_data {
  mat4 view_proj;       // world to clip of the camera (or of the light, in the shadow pass)
  mat4 inv_view_proj;   // clip to world of the camera
  mat4 view;            // world to view of the camera
  vec4 camera_position; // xyz; w: the projection's pixels across a unit at unit view depth (rough glass's blur)
  vec4 ambient;
  ivec4 size;           // xy: the image; zw: the shadow map
  vec4 params;          // x: refraction strength in pixels, y: shadow bias (a fraction of the receiver's
                        // distance from the light), z: the light whose shadow map hair reads (-1: none),
                        // w: k of the k-buffer
  mat4 to_previous;     // this frame's clip space to the previous frame's (temporal interlacing; else identity)
  mat4 from_previous;   // and back: the previous frame's clip space to this frame's
  ivec4 interlace;      // xy: added to a pixel before the interlace predicate (this frame's phase), z: 1
                        // when the second G-buffer holds the previous frame's, w: 1 when that frame was
                        // seen with this view_proj
  ivec4 counts;         // x: the lights in the light buffer (a Vulkan buffer is never empty, so the
                        // buffer's length() cannot tell no light from one)
};
)

DSTRANS_SHARED(dst_material_data,
struct dst_material_data {
  vec4 diffuse_alpha;
  vec4 specular;        // x: intensity, y: power, z: refractive, w: hair (drawn into the k-buffer)
  vec4 texture;         // x: its layer of the material textures (-1: none), y: the alpha cutoff (0: none),
                        // z: 1 where the texels' alpha multiplies alpha, w: the wrap modes, s + 3 t (dst_wrap)
};
)

DSTRANS_SHARED(dst_light_data,
struct dst_light_data {
  vec4 position_range;   // xyz, range
  vec4 direction_kind;   // xyz towards where it shines, w: 0 directional, 1 point, 2 spot
  vec4 colour_cos_outer; // rgb times intensity, cos of the outer angle
  vec4 cos_inner;        // x: cos of the inner angle, y: 1 when it casts shadows, z and w: its shadow map's
                         // near and far planes
  mat4 shadow_view_proj; // world to the shadow map's clip space
  mat4 volume;           // unit sphere or unit cone to world
};
)

static_assert(sizeof(dstrans::shader::dst_frame_data) == 416 && sizeof(dstrans::shader::dst_material_data) == 48 &&
                  sizeof(dstrans::shader::dst_light_data) == 192,
              "dstrans blocks: a block's C++ size differs from its std140/std430 size (GLM with padding?)");

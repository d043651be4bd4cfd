// What every dstrans pass knows about the frame, the materials and the lights (std140/std430, set 0).
// The C++ side mirrors these blocks in tools/frame_data.hpp; the bindings are the slot table of
// include/dstrans/frame/slots.hpp, which every pass gets as DST_SLOT_ defines.
#ifdef VULKAN
#define DST_VERTEX_ID gl_VertexIndex
#else
#define DST_VERTEX_ID gl_VertexID
#endif

layout(std140, binding = DST_SLOT_FRAME) uniform dst_frame {
  mat4 view_proj;       // world to clip of the camera (or of the light, in the shadow pass)
  mat4 inv_view_proj;   // clip to world of the camera
  mat4 view;            // world to view of the camera
  vec4 camera_position;
  vec4 ambient;
  ivec4 size;           // xy: the image; zw: the shadow map
  vec4 params;          // x: refraction strength in pixels, y: shadow depth bias, z: the light whose shadow
                        // map hair reads (-1: none), w: k of the k-buffer
} frame;

struct dst_material_data {
  vec4 diffuse_alpha;
  vec4 specular;        // x: intensity, y: power, z: refractive, w: hair (drawn into the k-buffer)
};
layout(std430, binding = DST_SLOT_MATERIALS) readonly buffer dst_materials { dst_material_data materials[]; };

struct dst_light_data {
  vec4 position_range;   // xyz, range
  vec4 direction_kind;   // xyz towards where it shines, w: 0 directional, 1 point, 2 spot
  vec4 colour_cos_outer; // rgb times intensity, cos of the outer angle
  vec4 cos_inner;        // x: cos of the inner angle, y: 1 when it casts shadows, z and w: its shadow map's
                         // near and far planes
  mat4 shadow_view_proj; // world to the shadow map's clip space
  mat4 volume;           // unit sphere or unit cone to world
};
layout(std430, binding = DST_SLOT_LIGHTS) readonly buffer dst_lights { dst_light_data lights[]; };

// What every dstrans pass knows about the frame, the materials and the lights (std140/std430, set 0): the
// blocks of include/dstrans/frame/blocks.hpp, which come with the names, at the slots of
// include/dstrans/frame/slots.hpp, which every pass gets as DST_SLOT_ defines.
#ifdef VULKAN
#define DST_VERTEX_ID gl_VertexIndex
#else
#define DST_VERTEX_ID gl_VertexID
#endif

layout(std140, binding = DST_SLOT_FRAME) uniform dst_frame { dst_frame_data frame; };
layout(std430, binding = DST_SLOT_MATERIALS) readonly buffer dst_materials { dst_material_data materials[]; };
layout(std430, binding = DST_SLOT_LIGHTS) readonly buffer dst_lights { dst_light_data lights[]; };

// What every post-processing pass reads (dstrans::post_pass): its first texture input, and its parameters;
// a pass with a second input declares it (binding 33). Taps past the image's border repeat the border.
layout(binding = DST_SLOT_POST_INPUT) uniform sampler2D dst_post_in0;
layout(std140, binding = DST_SLOT_POST_PARAMS) uniform dst_post_block { vec4 params; } post;
layout(location = 0) out vec4 dst_post_colour;

ivec2 dst_post_clamp(ivec2 p) { return clamp(p, ivec2(0), frame.size.xy - 1); }
vec4 dst_post_fetch0(ivec2 p) { return texelFetch(dst_post_in0, dst_post_clamp(p), 0); }

// The distance from the camera to what the G-buffer holds at p.
float dst_post_distance(ivec2 p, float depth) { return distance(dst_world_position(p, depth), frame.camera_position.xyz); }

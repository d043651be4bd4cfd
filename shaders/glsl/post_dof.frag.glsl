// Depth of field (S3): the frame where the G-buffer's surface is x world units from the camera, its
// blurred copy where it is y nearer or farther, and between them in proportion.
layout(binding = DST_SLOT_POST_INPUT + 1) uniform sampler2D dst_post_in1;

void main() {
  ivec2 p = dst_pixel();
  float amount = dst_blur_amount(dst_post_distance(p, dst_gbuffer_read(p).depth), post.params.x, post.params.y);
  dst_post_colour = mix(dst_post_fetch0(p), texelFetch(dst_post_in1, p, 0), amount);
}

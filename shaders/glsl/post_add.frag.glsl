// Bloom's last pass (S3): the frame plus x times the blurred bright pass.
layout(binding = DST_SLOT_POST_INPUT + 1) uniform sampler2D dst_post_in1;

void main() {
  ivec2 p = dst_pixel();
  vec4 c = dst_post_fetch0(p);
  dst_post_colour = vec4(c.rgb + post.params.x * texelFetch(dst_post_in1, p, 0).rgb, c.a);
}

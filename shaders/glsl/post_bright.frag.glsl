// Bloom's bright pass (S3): what is brighter than luminance x, scaled down by the threshold.
void main() {
  vec4 c = dst_post_fetch0(dst_pixel());
  dst_post_colour = vec4(dst_bright_pass(c.rgb, post.params.x), c.a);
}

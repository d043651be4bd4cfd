// One direction of the separable Gaussian blur (S3): x the radius in taps, y sigma in pixels, zw the
// direction, (1, 0) or (0, 1). The weights are divided by their sum, so a constant image stays constant.
void main() {
  ivec2 p = dst_pixel();
  int radius = int(post.params.x + 0.5f);
  ivec2 dir = ivec2(post.params.zw + 0.5f);
  vec4 sum = vec4(0.0f);
  float total = 0.0f;
  for (int i = -radius; i <= radius; ++i) {
    float w = dst_gaussian(float(i), post.params.y);
    sum += w * dst_post_fetch0(p + i * dir);
    total += w;
  }
  dst_post_colour = sum / total;
}

// Greyscale with S3's luminance weights, or with DST_SEPIA a sepia tone.
void main() {
  vec4 c = dst_post_fetch0(dst_pixel());
#ifdef DST_SEPIA
  dst_post_colour = vec4(dst_sepia(c.rgb), c.a);
#else
  dst_post_colour = vec4(dst_greyscale(c.rgb), c.a);
#endif
}

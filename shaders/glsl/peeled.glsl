// Where deferred depth peeling keeps the layer behind a pixel: at the same pixel of the second G-buffer
// and light buffer (the nearest opaque surface behind the first layer).
void dst_other_layer(ivec2 pixel, dst_surface here, out dst_surface s, out dst_light_sample light) {
  s = dst_gbuffer2_read(pixel);
  light = dst_light2_read(pixel);
}

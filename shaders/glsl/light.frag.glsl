// The light pass (thesis 3.2): additive blending, each pixel lit as the surface its G-buffer row holds.
layout(location = 0) flat in dst_light_varying light;

void main() {
  ivec2 pixel = dst_pixel();
  dst_surface s = dst_gbuffer_read(pixel);
  if (s.depth >= 1.0f) discard;  // nothing was drawn here
  dst_light_write(dst_light_at_point(dst_light_of(light), dst_world_position(pixel, s.depth), s.normal, s.spec_power));
}

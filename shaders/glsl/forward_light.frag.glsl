// One forward light pass: depth test less-or-equal against the ambient pass, no depth writes; the
// fragment's full shading under one light added to its colour (alpha untouched: it adds 0).
layout(location = 0) out vec4 colour;

void main() {
  dst_surface s;
  if (!dst_forward_surface(s)) discard;
  dst_light_sample l = dst_light_at_point(lights[light_id], world_position, s.normal, s.spec_power);
  colour = vec4(dst_shade(s, l, vec3(0.0f)), 0.0f);
}

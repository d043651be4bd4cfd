// The light pass: a full-screen triangle for directional lights, the light's volume mesh otherwise. The
// light's index comes as a per-instance attribute (first instance = the light), on GL and Vulkan alike.
#ifdef DST_LIGHT_VOLUME
layout(location = 0) in vec3 position;
#endif
layout(location = 3) in uint light_index;
layout(location = 0) flat out dst_light_varying light;

void main() {
  dst_light_data l = lights[light_index];
  light = dst_light_varying_of(l);
#ifdef DST_LIGHT_VOLUME
  gl_Position = frame.view_proj * (l.volume * vec4(position, 1.0f));
#else
  gl_Position = vec4(dst_fullscreen_position(DST_VERTEX_ID), 0.0f, 1.0f);
#endif
}

// G-buffer and shadow passes: the scene is one world-space mesh; frame.view_proj is the camera's or the light's.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in uint material;
layout(location = 0) out vec3 world_normal;
layout(location = 1) flat out uint surface_material;

#ifdef DST_TEXTURES
layout(location = 4) in vec2 uv;
layout(location = 4) out vec2 surface_uv;
#endif

void main() {
  world_normal = normal;
  surface_material = material;
  gl_Position = frame.view_proj * vec4(position, 1.0f);
#ifdef DST_TEXTURES
  surface_uv = uv;
#endif
}

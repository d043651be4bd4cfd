// Forward passes: the scene as one world-space mesh, with the light's index as a per-instance attribute
// (first instance = the light), as in light.vert.glsl.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in uint material;
layout(location = 3) in uint light_index;
layout(location = 0) out vec3 world_normal;
layout(location = 1) flat out uint surface_material;
layout(location = 2) out vec3 world_position;
layout(location = 3) flat out uint light_id;

#ifdef DST_TEXTURES
layout(location = 4) in vec2 uv;
layout(location = 4) out vec2 surface_uv;
#endif

void main() {
  world_normal = normal;
  surface_material = material;
  world_position = position;
  light_id = light_index;
  gl_Position = frame.view_proj * vec4(position, 1.0f);
#ifdef DST_TEXTURES
  surface_uv = uv;
#endif
}

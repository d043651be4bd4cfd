// The particle pass (S2): camera-facing quads built and sorted back to front on the CPU
// (dstrans::particle_quads), drawn over the frame.
layout(location = 0) in vec3 position;
layout(location = 1) in uint system;
layout(location = 2) in vec4 corner_alpha;  // xy: the corner in [-1, 1]^2, z: the particle's alpha share
layout(location = 0) out vec3 world;
layout(location = 1) flat out uint particle_system;
layout(location = 2) out vec3 particle_corner_alpha;

void main() {
  world = position;
  particle_system = system;
  particle_corner_alpha = corner_alpha.xyz;
  gl_Position = frame.view_proj * vec4(position, 1.0f);
}

// The particle pass (S2): camera-facing quads built and sorted back to front on the CPU
// (dstrans::particle_quads), drawn over the frame. What is the same over a particle is looked up here
// rather than at each of its fragments: its material and (light volumes) the texels of the cell at its
// centre, the sphere it stands for lit by the light there. Measured on smoke.json at 320x180 (8 cells a
// side, moments): RMSE 3.34 against the per-fragment reference where a read per fragment gave 3.23, and
// the particle pass took 7 ms where it took 22 on llvmpipe; texels fetched at the quad's corners and
// interpolated gave 4.27 (corners lie outside the disc, some outside the region).
layout(location = 0) in vec3 position;
layout(location = 1) in uint system;
layout(location = 2) in vec4 corner_alpha;  // xy: the corner in [-1, 1]^2, z: the particle's alpha share, w: its size
layout(location = 0) out vec3 world;
layout(location = 1) out vec3 particle_corner_alpha;
layout(location = 2) flat out vec4 particle_material;  // its material's diffuse colour and alpha
#ifndef DST_PARTICLES_FORWARD
layout(location = 3) flat out float particle_range;    // its region's range (dst_volume_light)
layout(location = 4) flat out vec4 particle_texels[DST_VOLUME_TEXELS];
#endif

struct dst_particle_region {
  vec4 origin_material;  // the region's first cell corner; w: the system's material
  vec4 scale_slab;       // a cell's size; w: the atlas's slab height
  vec4 offset_range;     // the region's first texel; w: its range
  vec4 dims;             // its cells per axis
};
layout(std430, binding = DST_SLOT_PARTICLE_REGIONS) readonly buffer dst_particle_regions { dst_particle_region regions[]; };
#ifndef DST_PARTICLES_FORWARD
layout(binding = DST_SLOT_VOLUME_ATLAS) uniform sampler3D dst_volume_atlas;
#endif

void main() {
  dst_particle_region region = regions[system];
  world = position;
  particle_corner_alpha = corner_alpha.xyz;
  particle_material = dst_material(uint(region.origin_material.w + 0.5f)).diffuse_alpha;
#ifndef DST_PARTICLES_FORWARD
  particle_range = region.offset_range.w;
  vec3 right = vec3(frame.view[0][0], frame.view[1][0], frame.view[2][0]);
  vec3 up = vec3(frame.view[0][1], frame.view[1][1], frame.view[2][1]);
  vec3 centre = position - corner_alpha.w * (corner_alpha.x * right + corner_alpha.y * up);
  dst_volume_texels(dst_volume_atlas, region.scale_slab.w, centre, region.origin_material.xyz, region.scale_slab.xyz,
                    region.offset_range.xyz, region.dims.xyz, particle_texels);
#endif
  gl_Position = frame.view_proj * vec4(position, 1.0f);
}

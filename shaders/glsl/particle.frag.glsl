// The particle pass (S2): a particle is a soft disc lit as the sphere it stands for (the normal from its
// corner, facing the camera at the centre), from the texels of the cell at its centre or
// (DST_PARTICLES_FORWARD, the reference) by every light per fragment with Lambert's law, and laid over the
// frame premultiplied, with in alpha the share of the frame that shows through (the blend keeps
// colour = source + frame * alpha); around the glass (DST_AROUND_GLASS), into the glass layer on its side of
// the pixel's glass, the other layer given nothing; in the exact reference (DST_EXACT), into the pixel's
// list (lists.glsl). A particle fades out near the opaque surface behind it.
layout(location = 0) in vec3 world;
layout(location = 1) in vec3 particle_corner_alpha;
layout(location = 2) flat in vec4 particle_material;
#ifndef DST_PARTICLES_FORWARD
layout(location = 3) flat in float particle_range;
layout(location = 4) flat in vec4 particle_texels[DST_VOLUME_TEXELS];
#endif
layout(location = 0) out vec4 dst_particle_colour;
#ifdef DST_AROUND_GLASS
layout(location = 1) out vec4 dst_particle_front;
#endif
#ifdef DST_EXACT
layout(location = 1) out float dst_particle_optical_depth;  // where the list is full: the tail targets'
#endif

// World units over which a particle fades out as it nears the surface behind it (soft particles): without
// it, quads cut the floor and walls along hard lines.
const float dst_particle_fade = 0.3f;

// The world position at window depth `depth` on the ray through the fragment at `p`: as
// dst_world_position, without a matrix product a fragment. Points of one pixel unproject to h(d) =
// h(z) + (d - z) * inv_view_proj[2], and h(z) = p * gl_FragCoord.w for the fragment's own depth z.
vec3 dst_behind(vec3 p, float depth) {
  vec4 along = frame.inv_view_proj[2];
  float delta = depth - gl_FragCoord.z;
  return (p * gl_FragCoord.w + delta * along.xyz) / (gl_FragCoord.w + delta * along.w);
}

#ifdef DST_PARTICLES_FORWARD
vec3 dst_particle_forward(vec3 p, vec3 n) {
  vec3 sum = vec3(0.0f);
  int layer = 0;
  for (int i = 0; i < frame.counts.x; ++i) {
    dst_light_data l = lights[i];
    vec4 reach = dst_light_reach(int(l.direction_kind.w + 0.5f), l.position_range.xyz, l.direction_kind.xyz,
                                 l.position_range.w, l.colour_cos_outer.w, l.cos_inner.x, p);
    vec3 light = l.colour_cos_outer.xyz * reach.w;
#ifdef DST_SHADOWS
    if (l.cos_inner.y > 0.5f) {
      dst_shadow_layer = layer++;
      light = dst_shadowed(light, p, l);
    }
#endif
    sum += light * dst_facing(n, reach.xyz);
  }
  return sum;
}
#endif

void main() {
  vec2 corner = particle_corner_alpha.xy;
  float r2 = dot(corner, corner);
  if (r2 >= 1.0f) discard;
  vec3 eye = frame.camera_position.xyz;
  vec2 glass = dst_glass_and_opaque(dst_pixel());
  float gap = distance(dst_behind(world, glass.y), eye) - distance(world, eye);
  if (!(gap > 0.0f)) discard;
  vec3 right = vec3(frame.view[0][0], frame.view[1][0], frame.view[2][0]);
  vec3 up = vec3(frame.view[0][1], frame.view[1][1], frame.view[2][1]);
  vec3 toward = vec3(frame.view[0][2], frame.view[1][2], frame.view[2][2]);
  vec3 n = normalize(corner.x * right + corner.y * up + sqrt(1.0f - r2) * toward);
#ifdef DST_PARTICLES_FORWARD
  vec3 light = dst_particle_forward(world, n);
#else
  vec3 light = dst_volume_light(particle_texels, n, particle_range);
#endif
  float soft = (1.0f - r2) * (1.0f - r2) * min(gap / dst_particle_fade, 1.0f);
  float a = clamp(particle_material.w * particle_corner_alpha.z * soft, 0.0f, 1.0f);
#ifdef DST_EXACT
  if (!(a > 0.0f)) discard;
  dst_particle_colour = dst_push_shaded(dst_pixel(), gl_FragCoord.z, vec4(particle_material.xyz * (frame.ambient.xyz + light), a),
                                        dst_particle_optical_depth);
  return;
#endif
  vec4 colour = vec4(particle_material.xyz * (frame.ambient.xyz + light) * a, 1.0f - a);
#ifdef DST_AROUND_GLASS
  bool behind = dst_behind_glass(gl_FragCoord.z, glass.x);
  vec4 none = vec4(0.0f, 0.0f, 0.0f, 1.0f);
  dst_particle_colour = behind ? colour : none;
  dst_particle_front = behind ? none : colour;
#else
  dst_particle_colour = colour;
#endif
}

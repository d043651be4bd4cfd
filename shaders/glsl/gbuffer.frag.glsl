// The G-buffer pass (thesis 3.1.1): depth test and write on, blending off. A transparent fragment is
// kept only where the interlace predicate allows; transparent materials are double-sided, their normal
// turned to face the viewer.
layout(location = 0) in vec3 world_normal;
layout(location = 1) flat in uint surface_material;

void main() {
  dst_material_data m = materials[surface_material];
  bool transparent = m.diffuse_alpha.w < 1.0f;
  if (transparent && !dst_interlace_keep(dst_pixel(), frame.size.xy)) discard;
  dst_surface s = dst_surface_zero();
  s.diffuse = m.diffuse_alpha.xyz;
  s.alpha = m.diffuse_alpha.w;
  s.normal = normalize(gl_FrontFacing || !transparent ? world_normal : -world_normal);
  s.spec_intensity = m.specular.x;
  s.spec_power = m.specular.y;
  s.depth = gl_FragCoord.z;
  dst_gbuffer_write(s);
}

// What the forward passes share (thesis 4.1.3): every pass draws all geometry with the same interlace
// discard, so the same fragment wins each pixel in every pass.
layout(location = 0) in vec3 world_normal;
layout(location = 1) flat in uint surface_material;
layout(location = 2) in vec3 world_position;
layout(location = 3) flat in uint light_id;

// The material's surface at this fragment, or false where the interlace predicate drops it.
bool dst_forward_surface(out dst_surface s) {
  dst_material_data m = materials[surface_material];
  bool transparent = m.diffuse_alpha.w < 1.0f;
  s = dst_surface_zero();
  s.diffuse = m.diffuse_alpha.xyz;
  s.alpha = m.diffuse_alpha.w;
  s.normal = normalize(gl_FrontFacing || !transparent ? world_normal : -world_normal);
  s.spec_intensity = m.specular.x;
  s.spec_power = m.specular.y;
  s.depth = gl_FragCoord.z;
  return !transparent || dst_interlace_keep(dst_pixel(), frame.size.xy);
}

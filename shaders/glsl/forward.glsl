// What the forward passes share (thesis 4.1.3): every pass draws all geometry with the same interlace
// discard, so the same fragment wins each pixel in every pass.
layout(location = 0) in vec3 world_normal;
layout(location = 1) flat in uint surface_material;
layout(location = 2) in vec3 world_position;
layout(location = 3) flat in uint light_id;

// The material's surface at this fragment, or false where the interlace predicate drops it.
bool dst_forward_surface(out dst_surface s) {
  dst_material_data m = dst_material(surface_material);
  s = dst_material_surface(m, world_normal);
  return !dst_transparent(s.alpha) || dst_interlace_keep(dst_pixel(), frame.size.xy);
}

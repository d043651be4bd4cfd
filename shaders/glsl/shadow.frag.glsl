// The shadow pass of one spot light (thesis 3.2.1, Table 3.3): as the G-buffer pass, seen from the light,
// storing the occluder's depth, colour and alpha. With plain shadow maps only the depth is stored.
layout(location = 0) in vec3 world_normal;
layout(location = 1) flat in uint surface_material;

void main() {
  dst_material_data m = materials[surface_material];
#ifdef DST_TRANSPARENT_SHADOWS
  if (m.diffuse_alpha.w < 1.0f && !dst_interlace_keep(dst_pixel(), frame.size.zw)) discard;
#endif
  dst_shadow_write(dst_material_surface(m, world_normal));
}

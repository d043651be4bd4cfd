// The shadow pass of one spot light (thesis 3.2.1, Table 3.3): as the G-buffer pass, seen from the light,
// storing the occluder's depth, colour and alpha. With plain shadow maps only the depth is stored.
layout(location = 0) in vec3 world_normal;
layout(location = 1) flat in uint surface_material;

void main() {
  dst_material_data m = dst_material(surface_material);
  dst_surface s = dst_material_surface(m, world_normal);
#ifdef DST_MANY_LAYERS
  // Hair occludes what lies behind it fully here; hair itself reads its depth with Eq. 1 (resolve pass).
  if (m.specular.w > 0.5f) s.alpha = 1.0f;
#endif
#ifdef DST_TRANSPARENT_SHADOWS
  if (dst_transparent(s.alpha) && !dst_interlace_keep(dst_pixel(), frame.size.zw)) discard;
#endif
  dst_shadow_write(s);
}

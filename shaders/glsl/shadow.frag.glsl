// The shadow pass of one spot light (thesis 3.2.1, Table 3.3): as the G-buffer pass, seen from the light,
// storing the occluder's depth, colour and alpha. With plain shadow maps only the depth is stored. With
// DST_DEPTH_ONLY it is the pass of a transparent map's opaque surfaces (frame_plan::depth_only_shadows):
// their depth and the clear colour, opaque white, without their material, as no lookup reads an opaque
// occluder's colour.
layout(location = 0) in vec3 world_normal;
layout(location = 1) flat in uint surface_material;

void main() {
#ifdef DST_DEPTH_ONLY
  dst_surface s = dst_surface_zero();
  s.diffuse = vec3(1.0f);
  s.alpha = 1.0f;
  s.depth = gl_FragCoord.z;
#else
  dst_material_data m = dst_material(surface_material);
  dst_surface s = dst_material_surface(m, world_normal);
#ifdef DST_MANY_LAYERS
  // Hair occludes what lies behind it fully here; hair itself reads its depth with Eq. 1 (resolve pass).
  if (m.specular.w > 0.5f) s.alpha = 1.0f;
#endif
#ifdef DST_TRANSPARENT_SHADOWS
  if (dst_transparent(s.alpha) && !dst_interlace_keep(dst_pixel(), frame.size.zw)) discard;
#endif
#endif
  dst_shadow_write(s);
}

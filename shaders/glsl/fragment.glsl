// What every dstrans fragment shader knows besides frame.glsl.

// The pixel a fragment covers, rows from the top on both APIs.
ivec2 dst_pixel() { return ivec2(gl_FragCoord.xy); }

// The world position a camera pixel shows at window depth `depth` (through the inverse projection).
vec3 dst_world_position(ivec2 pixel, float depth) {
  vec4 h = frame.inv_view_proj * vec4(dst_pixel_ndc(pixel, frame.size.xy), depth, 1.0f);
  return h.xyz / h.w;
}

// The surface of a fragment of `m` with interpolated normal `normal`: transparent materials are
// double-sided, their normal turned to face the viewer.
dst_surface dst_material_surface(dst_material_data m, vec3 normal) {
  bool transparent = dst_transparent(m.diffuse_alpha.w);
  dst_surface s = dst_surface_zero();
  s.diffuse = m.diffuse_alpha.xyz;
  s.alpha = m.diffuse_alpha.w;
  s.normal = normalize(gl_FrontFacing || !transparent ? normal : -normal);
  s.spec_intensity = m.specular.x;
  s.spec_power = m.specular.y;
  s.depth = gl_FragCoord.z;
  return s;
}

// What every dstrans fragment shader knows besides frame.glsl.

// The pixel a fragment covers, rows from the top on both APIs.
ivec2 dst_pixel() { return ivec2(gl_FragCoord.xy); }

// The world position a camera pixel shows at window depth `depth` (through the inverse projection).
vec3 dst_world_position(ivec2 pixel, float depth) {
  vec4 h = frame.inv_view_proj * vec4(dst_pixel_ndc(pixel, frame.size.xy), depth, 1.0f);
  return h.xyz / h.w;
}

#ifdef DST_TEXTURES
// The fragment's texture coordinates (location 4 in every geometry pass) and the scene's textures.
layout(location = 4) in vec2 dst_surface_uv;
layout(binding = DST_SLOT_MATERIAL_TEXTURES) uniform sampler2DArray dst_material_textures;

// Coordinate `c` of a texture `size` texels wide as wrap mode `mode` reads it (scene.hpp's wrap: 0 repeat,
// 1 clamped to the edge texels' centres, 2 mirrored repeat); the sampler itself repeats.
float dst_wrap(float c, int mode, float size) {
  if (mode == 1) return clamp(c, 0.5f / size, 1.0f - 0.5f / size);
  if (mode == 2) return 1.0f - abs(mod(c, 2.0f) - 1.0f);
  return c;
}

// The texel of material `m` at this fragment (white without a texture). The mip level comes from the
// unwrapped coordinates' derivatives, taken before any fragment of the quad is discarded, so that a wrap's
// seam does not pick the coarsest level.
vec4 dst_material_texel(dst_material_data m) {
  vec2 dx = dFdx(dst_surface_uv), dy = dFdy(dst_surface_uv);
  if (m.texture.x < 0.0f) return vec4(1.0f);
  int modes = int(m.texture.w + 0.5f);
  vec2 size = vec2(textureSize(dst_material_textures, 0).xy);
  vec2 uv = vec2(dst_wrap(dst_surface_uv.x, modes % 3, size.x), dst_wrap(dst_surface_uv.y, modes / 3, size.y));
  return textureGrad(dst_material_textures, vec3(uv, m.texture.x), dx, dy);
}
#endif

// The surface of a fragment of `m` with interpolated normal `normal`: transparent materials are
// double-sided, their normal turned to face the viewer. With DST_TEXTURES the material's texel multiplies
// its colour (and its alpha, where m.texture.z says), and an alpha-tested material drops the fragment
// below its cutoff and is opaque elsewhere.
dst_surface dst_material_surface(dst_material_data m, vec3 normal) {
  vec4 colour = m.diffuse_alpha;
#ifdef DST_TEXTURES
  vec4 texel = dst_material_texel(m);
  colour.xyz *= texel.xyz;
  if (m.texture.z > 0.5f) colour.w *= texel.w;
  if (m.texture.y > 0.0f) {
    if (colour.w < m.texture.y) discard;
    colour.w = 1.0f;
  }
#endif
  bool transparent = dst_transparent(colour.w);
  dst_surface s = dst_surface_zero();
  s.diffuse = colour.xyz;
  s.alpha = colour.w;
  s.normal = normalize(gl_FrontFacing || !transparent ? normal : -normal);
  s.spec_intensity = m.specular.x;
  s.spec_power = m.specular.y;
  s.depth = gl_FragCoord.z;
  return s;
}

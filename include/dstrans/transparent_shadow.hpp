// Coloured shadows from transparent occluders (the thesis, 3.2.1, Eq. 3.1 and 3.2).
//
// A shadow map rendered with an interlace predicate holds, for a transparent occluder, its depth and
// colour on keep-pixels and the opaque occluder behind it on their partners. A lookup samples the texel
// and its partner; the one with the lower alpha is the transparent candidate (d_minA, C_minA), the
// other the opaque one (d_maxA). For a point at light-space depth d_P and a bias b (d = d_P - b):
//   I = 0                                  if d_maxA < d
//   I = min(I_L, C_minA) (1 - alpha_minA)  if d_minA < d <= d_maxA     (min per channel, Eq. 3.2)
//   I = I_L                                otherwise
//
//   glm::vec3 lit = dstrans::shader::dst_transparent_shadow(light, d_p, bias, depth_a, occluder_a, depth_b, occluder_b);
//
// Choices, each one of the project's tested hard cases:
// - equal alphas make the texel itself the transparent candidate;
// - two opaque samples (both alphas 1): the texel alone decides, as a plain shadow map does. The partner
//   is a neighbour's surface, not a layer behind this one; taking its depth as d_maxA would grow every
//   opaque shadow by a row;
// - two transparent samples (the predicate "none", or a 1-row map) know no opaque occluder: light is
//   filtered by the candidate where it lies in front of the point, never blocked;
// - alpha below 1 is transparent, even one RGBA8 code below (254/255 lets 1/255 of the light through);
//   alpha 0 glass still filters light by min(I_L, C), which is Eq. 3.2 as written;
// - the bias moves the point towards the light (a positive bias removes self-shadowing acne); a point at
//   exactly an occluder's depth is not behind it;
// - a point beyond the far plane (d_P - b > 1, or NaN) is taken at the far plane: the cleared map (depth
//   1) does not shadow it, occluders the map holds do;
// - NaN is decided before any comparison, so that no compiler's folding of a comparison decides it: a
//   NaN alpha is opaque (dst_transparent), a NaN occluder depth is the cleared map's 1, and a NaN channel
//   of the light or of the occluder's colour is 0;
// - the renderer compares linear depths, as fractions of the map's far plane: dst_shadow_linear_depth turns
//   a perspective map's window depth (0 at near, 1 at far; NaN as the cleared 1) into one, so that the
//   bias can be a fraction of the receiver's distance and a uniformly scaled scene keeps its shadows;
//   dst_ortho_linear_depth does the same for an orthographic map (a directional light's), whose window
//   depth is linear already;
// - dst_opaque_shadow is the plain shadow map the thesis compares with, looked up at the texel only.
// dst_shadow_case says which line of Eq. 3.1 applies (0 blocked, 1 through the transparent candidate, 2
// lit) for both transmittances.
// Eq. 3.2's min(I_L, C) is the default, as in the thesis: it only darkens a channel where the light is
// brighter than the glass, so a light of intensity 1 or more through glass of colour C gives C(1 - alpha)
// whatever its brightness, and dim light passes glass almost uncoloured. dst_transmitted_shadow offers the
// physically based transmittance I_L C (1 - alpha) instead: each channel scaled by the glass's colour.
#pragma once

#include "detail/shared.hpp"
#include "fullscreen.hpp"
#include "surface.hpp"

DSTRANS_SHARED(dst_opaque_shadow,
DST_FN float dst_clamp_window_depth(float window_depth) {
  return isnan(window_depth) ? 1.0f : (window_depth < 0.0f ? 0.0f : (window_depth > 1.0f ? 1.0f : window_depth));
}
DST_FN float dst_shadow_linear_depth(float window_depth, float near_plane, float far_plane) {
  return near_plane / (far_plane - dst_clamp_window_depth(window_depth) * (far_plane - near_plane));
}
DST_FN float dst_ortho_linear_depth(float window_depth, float near_plane, float far_plane) {
  return (near_plane + dst_clamp_window_depth(window_depth) * (far_plane - near_plane)) / far_plane;
}
DST_FN float dst_shadow_depth(float d_p, float bias) {
  float d = d_p - bias;
  return isnan(d) || d >= 1.0f ? 1.0f : d;
}
DST_FN vec3 dst_opaque_shadow(vec3 light, float d_p, float bias, float depth) {
  return depth < dst_shadow_depth(d_p, bias) ? vec3(0.0f) : light;
}
)

// A point light's shadow map is a cube: six square perspective maps of 90 degrees, one a face, drawn as
// tiles of the one map (three across, two down, each an even number of texels a side starting on an even
// texel, so that the interlace keeps its rows within a tile). A point belongs to the face of the largest
// component of its offset d from the light (ties to the lower face: +x, -x, +y, -y, +z, -z; NaN to the
// last, decided before any comparison as every shared formula decides NaN), and
// dst_cube_face_view turns d into that face's view space (looking down -z, as glm::lookAt along the face's
// axis with up +y, or +x for the faces along y), which the face's projection takes to its tile.
DSTRANS_SHARED(dst_cube_map,
DST_FN int dst_cube_face(vec3 d) {
  if (isnan(d.x) || isnan(d.y) || isnan(d.z)) return 5;
  vec3 a = abs(d);
  if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0f ? 0 : 1;
  if (a.y >= a.z) return d.y >= 0.0f ? 2 : 3;
  return d.z >= 0.0f ? 4 : 5;
}
DST_FN vec3 dst_cube_face_view(vec3 d, int face) {
  if (face == 0) return vec3(d.z, d.y, -d.x);
  if (face == 1) return vec3(-d.z, d.y, d.x);
  if (face == 2) return vec3(-d.z, d.x, -d.y);
  if (face == 3) return vec3(d.z, d.x, d.y);
  if (face == 4) return vec3(-d.x, d.y, -d.z);
  return d;
}
DST_FN int dst_cube_tile_size(ivec2 size) {
  int t = min(size.x / 3, size.y / 2);
  return t < 4 ? 2 : t - t % 2;
}
DST_FN ivec2 dst_cube_tile_origin(int face, ivec2 size) {
  int f = face < 0 ? 0 : (face > 5 ? 5 : face);
  return ivec2(f % 3, f / 3) * dst_cube_tile_size(size);
}
)

// A light's shadow map, as the light block describes it (dst_light_data's cos_inner: y 1 for a spot light's
// perspective map, 2 for a directional light's orthographic one, 3 for a point light's cube; z and w the
// near and far planes): a texel's window depth, and a point's clip position in the map, as the fractions
// of the far plane the lookups compare. A perspective clip position's w is the distance along the light's
// (or the cube face's) axis.
// A lookup takes a world point p to the map's view (dst_map_view_point: p itself but for a cube, whose
// face's view the light block's projection follows), finds the tile that holds it (the whole map but for
// a cube) and the texel under its normalized device coordinates (dst_map_texel: clamped to a cube's
// tile, which always holds the point; outside another map's, where the map does not reach). The
// partner of an interlaced texel is the one on the other side where the interlace's own lies outside the
// tile (dst_tile_partner), so that no lookup reads another face.
DSTRANS_SHARED(dst_shadow_map,
DST_FN bool dst_map_orthographic(vec4 map) { return map.y > 1.5f && map.y < 2.5f; }
DST_FN bool dst_map_cube(vec4 map) { return map.y > 2.5f; }
DST_FN float dst_map_depth(float window_depth, vec4 map) {
  return dst_map_orthographic(map) ? dst_ortho_linear_depth(window_depth, map.z, map.w)
                                   : dst_shadow_linear_depth(window_depth, map.z, map.w);
}
DST_FN float dst_map_point_depth(vec4 clip, vec4 map) {
  return dst_map_orthographic(map) ? dst_ortho_linear_depth(clip.z / clip.w, map.z, map.w) : clip.w / map.w;
}
DST_FN vec3 dst_map_view_point(vec3 p, vec3 light_position, vec4 map) {
  if (!dst_map_cube(map)) return p;
  vec3 d = p - light_position;
  return dst_cube_face_view(d, dst_cube_face(d));
}
DST_FN ivec2 dst_map_tile_origin(vec3 p, vec3 light_position, vec4 map, ivec2 size) {
  return dst_map_cube(map) ? dst_cube_tile_origin(dst_cube_face(p - light_position), size) : ivec2(0);
}
DST_FN ivec2 dst_map_tile_extent(vec4 map, ivec2 size) { return dst_map_cube(map) ? ivec2(dst_cube_tile_size(size)) : size; }
// Tile arithmetic is unsigned where int could overflow: it wraps, as GLSL's does.
DST_FN bool dst_tile_holds(ivec2 texel, ivec2 origin, ivec2 extent) {
  return texel.x >= origin.x && texel.y >= origin.y && uint(texel.x) - uint(origin.x) < uint(max(extent.x, 0)) &&
         uint(texel.y) - uint(origin.y) < uint(max(extent.y, 0));
}
DST_FN int dst_tile_column(float at, int extent) {
  if (!(at >= 0.0f) || extent < 1) return 0;
  return at < float(extent) ? min(int(floor(at)), extent - 1) : extent - 1;
}
DST_FN ivec2 dst_map_texel(vec2 ndc, ivec2 origin, ivec2 extent, vec4 map) {
  vec2 at = dst_ndc_window(ndc, extent);
  bool inside = at.x >= 0.0f && at.y >= 0.0f && at.x < float(extent.x) && at.y < float(extent.y);
  if (!dst_map_cube(map) && !inside) return ivec2(uvec2(origin) - uvec2(1u));
  return ivec2(uvec2(origin) + uvec2(ivec2(dst_tile_column(at.x, extent.x), dst_tile_column(at.y, extent.y))));
}
DST_FN ivec2 dst_tile_partner(ivec2 texel, ivec2 partner, ivec2 origin, ivec2 extent) {
  if (dst_tile_holds(partner, origin, extent)) return partner;
  ivec2 mirrored = ivec2(uvec2(texel) * 2u - uvec2(partner));
  return dst_tile_holds(mirrored, origin, extent) ? mirrored : texel;
}
)

DSTRANS_SHARED(dst_transparent_shadow,
DST_FN float dst_shadow_alpha(float alpha) { return dst_transparent(alpha) ? alpha : 1.0f; }
DST_FN float dst_shadow_texel_depth(float depth) { return isnan(depth) ? 1.0f : depth; }
DST_FN vec3 dst_nan_to_zero(vec3 v) {
  return vec3(isnan(v.x) ? 0.0f : v.x, isnan(v.y) ? 0.0f : v.y, isnan(v.z) ? 0.0f : v.z);
}
DST_FN bool dst_shadow_texel_transparent(vec4 occluder_a, vec4 occluder_b) {
  return dst_shadow_alpha(occluder_a.w) <= dst_shadow_alpha(occluder_b.w);
}
DST_FN int dst_shadow_case(float d_p, float bias, float depth_a, vec4 occluder_a, float depth_b, vec4 occluder_b) {
  float d = dst_shadow_depth(d_p, bias);
  float da = dst_shadow_texel_depth(depth_a), db = dst_shadow_texel_depth(depth_b);
  bool a_transparent = dst_shadow_texel_transparent(occluder_a, occluder_b);
  bool a_opaque = !dst_transparent(occluder_a.w), b_opaque = !dst_transparent(occluder_b.w);
  if (a_transparent && a_opaque) return da < d ? 0 : 2;
  float d_min = a_transparent ? da : db;
  float d_max = a_transparent ? db : da;
  if ((a_opaque || b_opaque) && d_max < d) return 0;
  if (d_min < d) return 1;
  return 2;
}
DST_FN vec3 dst_shadowed_light(vec3 light, bool physical, float d_p, float bias, float depth_a, vec4 occluder_a,
                               float depth_b, vec4 occluder_b) {
  int k = dst_shadow_case(d_p, bias, depth_a, occluder_a, depth_b, occluder_b);
  vec3 l = dst_nan_to_zero(light);
  if (k == 0) return vec3(0.0f);
  if (k == 2) return l;
  vec4 t = dst_shadow_texel_transparent(occluder_a, occluder_b) ? occluder_a : occluder_b;
  vec3 c = dst_nan_to_zero(vec3(t.x, t.y, t.z));
  vec3 filtered = physical ? l * c : min(l, c);
  return filtered * (1.0f - dst_shadow_alpha(t.w));
}
DST_FN vec3 dst_transparent_shadow(vec3 light, float d_p, float bias, float depth_a, vec4 occluder_a, float depth_b,
                                   vec4 occluder_b) {
  return dst_shadowed_light(light, false, d_p, bias, depth_a, occluder_a, depth_b, occluder_b);
}
DST_FN vec3 dst_transmitted_shadow(vec3 light, float d_p, float bias, float depth_a, vec4 occluder_a, float depth_b,
                                   vec4 occluder_b) {
  return dst_shadowed_light(light, true, d_p, bias, depth_a, occluder_a, depth_b, occluder_b);
}
)

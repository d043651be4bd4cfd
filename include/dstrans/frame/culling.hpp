// What a geometry pass draws of a scene: the objects of the set it asks for (draws, for an engine's own
// meshes by their dstrans material), less those outside the clip volume it draws them with
// (scheduled_pass::view_proj), and which of them it may draw with their back faces culled. An object whose
// bounding sphere lies wholly outside one of the volume's planes has no triangle that could reach a pixel,
// so leaving it out changes no pixel; it saves the object's vertices and triangle setup, a third of a
// point light's shadow pass on a CPU rasteriser, whose six cube faces each see a part of the scene. A
// closed object's back faces lie behind its front faces, so a shadow pass need not rasterise them: on a
// CPU rasteriser that halves the triangles set up and binned, the larger part of a shadow map's time.
//
//   const dstrans::scene_mesh m = dstrans::flatten(s);
//   for (const dstrans::index_run& run : dstrans::visible_runs(m.parts, m.hair_first, m.indices.size(), pass))
//     draw_my_indices(run.first, run.count, run.cull_back);   // back faces culled where cull_back says
//   // or, for an engine's own meshes, each with its dstrans material:
//   if (dstrans::draws(pass.draws, s.materials[mesh.material])) draw_my_mesh(mesh);
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "../scene.hpp"
#include "schedule.hpp"

namespace dstrans {

// Whether a pass that draws `set` draws an object of material `m`: hair alone in `hair`, never in
// `surfaces`; `opaque` the material::opaque() ones, `not_opaque` the others (options::opaque_shadows_depth_only).
inline bool draws(geometry_set set, const material& m) {
  switch (set) {
    case geometry_set::none: return false;
    case geometry_set::surfaces: return !m.hair;
    case geometry_set::hair: return m.hair;
    case geometry_set::everything: return true;
    case geometry_set::opaque: return m.opaque();
    case geometry_set::not_opaque: return !m.opaque();
  }
  return false;
}

// Whether the sphere at `centre` of `radius` (world space) lies wholly outside the clip volume of
// `view_proj`: beyond one of its planes -w <= x <= w, -w <= y <= w and, unless `depth_clamped` (depth
// clamping draws what lies beyond the near and far planes), -w <= z <= w. That near plane is OpenGL's;
// it holds Vulkan's (0 <= z), so neither API's picture loses a pixel. The sphere is widened by 1e-4 of
// its size against rounding. A zero matrix culls nothing, and nor does a NaN anywhere.
inline bool outside_clip(const glm::mat4& view_proj, glm::vec3 centre, float radius, bool depth_clamped) {
  const glm::mat4 rows = glm::transpose(view_proj);
  const glm::vec4 planes[6] = {rows[3] + rows[0], rows[3] - rows[0], rows[3] + rows[1],
                               rows[3] - rows[1], rows[3] + rows[2], rows[3] - rows[2]};
  const float margin = radius + 1e-4f * (radius + glm::length(centre)) + 1e-6f;
  for (int k = 0; k < (depth_clamped ? 4 : 6); ++k) {
    const glm::vec3 n(planes[k]);
    const float length = glm::length(n), value = glm::dot(n, centre) + planes[k].w;
    if (length > 0.0f ? value < -margin * length : value < 0.0f) return true;
  }
  return false;
}

// Whether `pass` may draw the part with its back faces culled: the pass keeps the nearest surface
// (pass_state::cull_closed), the part is closed (mesh_part::closed) and its sphere lies wholly beyond the
// near plane of the pass's clip volume: beyond -w <= z and 0 <= z both, so that a matrix for either depth
// range (OpenGL's default, or Vulkan's, which dstrans uses on both APIs) is taken at its own near plane or
// farther. The viewpoint then lies outside the part and no plane cuts it open, so every ray from the
// viewpoint meets one of its front faces before any of its back faces, and culling these changes no
// pixel, but on a silhouette: where a front and a back face meet, their interpolated depths can round
// apart, and the back face win a texel by an ulp; culled, the front face keeps it, as exact depths would.
// The shadow passes alone ask for it: a G-buffer texel holds the winner's normal, and culled G-buffer
// passes moved a glass pixel of a temporal frame 2 codes away from depth peeling's. The margin is
// outside_clip's; a zero or NaN matrix culls no faces.
inline bool culls_back_faces(const scheduled_pass& pass, const mesh_part& part) {
  if (!pass.state.cull_closed || !part.closed) return false;
  const glm::mat4 rows = glm::transpose(pass.view_proj);
  const float margin = part.radius + 1e-4f * (part.radius + glm::length(part.centre)) + 1e-6f;
  for (const glm::vec4& plane : {rows[3] + rows[2], rows[2]}) {
    const float length = glm::length(glm::vec3(plane));
    if (!(length > 0.0f) || !(glm::dot(glm::vec3(plane), part.centre) + plane.w > margin * length)) return false;
  }
  return true;
}

// The runs of indices `pass` draws of a flattened scene (scene_mesh: its `parts` in index order, hair from
// `hair_first`, `count` indices in all): drawn_indices' run less the parts outside the pass's clip
// volume, neighbouring parts drawn as one run where both may cull their back faces or neither
// (culls_back_faces: index_run::cull_back); `opaque` and `not_opaque` take the parts whose mesh_part::opaque
// says so. Without parts, drawn_indices' run, which culls no faces.
inline std::vector<index_run> visible_runs(const std::vector<mesh_part>& parts, std::size_t hair_first, std::size_t count,
                                           const scheduled_pass& pass) {
  const bool by_material = pass.draws == geometry_set::opaque || pass.draws == geometry_set::not_opaque;
  const index_run whole = by_material && !parts.empty() ? index_run{0, count} : drawn_indices(pass.draws, hair_first, count);
  if (whole.count == 0) return {};
  if (parts.empty()) return {whole};
  std::vector<index_run> out;
  for (const mesh_part& part : parts) {
    if (part.first < whole.first || part.first + part.count > whole.first + whole.count || part.count == 0) continue;
    if (by_material && part.opaque != (pass.draws == geometry_set::opaque)) continue;
    if (outside_clip(pass.view_proj, part.centre, part.radius, pass.state.depth_clamp)) continue;
    const bool cull = culls_back_faces(pass, part);
    if (!out.empty() && out.back().first + out.back().count == part.first && out.back().cull_back == cull)
      out.back().count += part.count;
    else
      out.push_back({part.first, part.count, cull});
  }
  return out;
}

}  // namespace dstrans

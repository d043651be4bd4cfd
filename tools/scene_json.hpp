// Scene files (examples/scenes/*.json) into dstrans::scene, with an error that names the offending field.
//
//   auto s = dstrans::load_scene("examples/scenes/glass_room.json");
//   if (!s) std::fprintf(stderr, "%s\n", s.error().c_str());   // "glass_room.json: objects[3].size[1]: ..."
//
// The format (every key is checked; unknown keys are errors, so a typo does not pass silently):
//   {"camera": {"position": [x,y,z], "target": [x,y,z], "fov_y": deg, "near": n, "far": f},
//    "ambient": [r,g,b],
//    "materials": {"name": {"diffuse": [r,g,b], "alpha": a, "spec_intensity": s, "spec_power": p,
//                           "refractive": bool, "hair": bool}, ...},
//    "objects": [{"shape": "box"|"room"|"pane"|"sphere"|"cylinder"|"bottle"|"hair", "material": "name",
//                 "position": [x,y,z], "rotation_y": deg, "rotation_x": deg (after the turn about Y),
//                 shape parameters...}
//                or {"gltf": "file.gltf|.glb", "position", "rotation_y", "rotation_x", "scale": s}, ...],
//    "lights": [{"type": "directional"|"point"|"spot", "colour": [r,g,b], "intensity": i,
//                "position": [x,y,z], "direction": [x,y,z], "range": r, "inner_angle": deg,
//                "outer_angle": deg, "shadows": bool}, ...],
//    "particles": [{"material": "name", "base": [x,y,z], "radius": r, "height": h, "size": s,
//                   "count": n, "seed": k}, ...],
//    "post": [{"effect": "blur"|"bloom"|"dof"|"greyscale"|"sepia"|"aa", parameters...}, ...]}
// An object of "gltf" places a glTF asset (scene_gltf.hpp; its path relative to the scene file's folder):
// its meshes and materials, scaled by "scale" (1 unless given), then turned and moved as a shape is; the
// asset's cameras and lights are not the scene's.
// Shape parameters: box and room "size": [x,y,z]; pane "size": [w,h]; sphere "radius"; cylinder and
// bottle "radius", "height"; sphere, cylinder and bottle "segments" (default 32); hair "radius" (of the
// scalp), "strands", "length", "width" (default 0.01), "segments" (default 8), "seed" (default 1).
// A spot light with "shadows" casts them from a map whose near and far planes are where the scene's bounds
// begin and end seen from it (within its range); a directional one from an orthographic map over the
// scene's bounding sphere (a texel spans its diameter over --shadow-size); a point one from a cube of six
// 90-degree faces, each a tile of the map (a third of --shadow-size a side). Receivers are biased by a
// fraction of their distance from the map's eye (dstrans render --shadow-bias, 0.005 unless given) and
// moved a texel along their normal, so a scene's shadows do not depend on its scale or units.
// Particle systems (dstrans::particle_system): radius 0.5, height 2, size 0.25, count 100, seed 1 unless given.
// Post effects (dstrans::post_effect, run in order after the frame): blur, bloom and dof "radius" (taps, 4)
// and "sigma" (2); bloom "threshold" (0.8) and "intensity" (1); dof "focus" (5) and "range" (2); aa
// "normal_scale" (4), "depth_scale" (20), "strength" (1/3) and "interlace" (true). A file of {"post": [...]} alone is a chain.
#pragma once

#include <cstddef>
#include <string>

#include <dstrans/result.hpp>
#include <dstrans/scene.hpp>

namespace dstrans {

// What a scene may take. Its cost is estimated from the file's numbers before each object, particle
// system or light is built (the memory they take in the renderer, CPU and GPU together, measured on Mesa:
// about 210 bytes a vertex and 930 a particle), and a scene over `bytes` is refused with its estimate. A
// file larger than `file_bytes`, or one that is not a plain file (a folder, /dev/zero), is refused unread.
struct scene_budget {
  std::size_t bytes = std::size_t(1) << 30;
  std::size_t file_bytes = std::size_t(64) << 20;
};
inline constexpr std::size_t bytes_per_vertex = 256, bytes_per_particle = 1024, bytes_per_light = 1024;
// `bytes` in MiB, rounded up, as a budget's messages give them.
std::string mib(std::size_t bytes);
// The estimate for a built scene (its vertices, particles and lights).
std::size_t scene_bytes(const scene& s);

// The scene in file `path` (JSON, or glTF where the name ends .gltf or .glb: scene_gltf.hpp), or a
// sentence naming the file and field that is wrong.
result<scene> load_scene(const std::string& path, const scene_budget& budget = {});
// The scene in JSON text `text`; `name` prefixes error messages.
result<scene> parse_scene(const std::string& text, const std::string& name, const scene_budget& budget = {});
// The bytes of plain file `path` (a `what`, as errors name it), refused unread above `limit` bytes.
result<std::string> read_input_file(const std::string& path, const char* what, std::size_t limit);
// A post-processing chain alone: a file or text of {"post": [...]}, to run after any scene.
result<std::vector<post_effect>> load_post_chain(const std::string& path);
result<std::vector<post_effect>> parse_post_chain(const std::string& text, const std::string& name);

}  // namespace dstrans

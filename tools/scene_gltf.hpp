// glTF 2.0 assets (.gltf, .glb) into dstrans::scene, with an error that names the file and the element.
//
//   auto s = dstrans::load_gltf("assets/room.glb");
//   if (!s) std::fprintf(stderr, "%s\n", s.error().c_str());
//   // "room.glb: meshes[2].primitives[0].attributes.POSITION[7]: not a finite position (inf)"
//
// What is read, and how glTF's physically based description becomes dstrans's (approximations named):
// - The default scene's nodes (the first scene's where none is named; every node no other node holds where
//   the file has no scene), with their matrix or translation, rotation and scale, down every child. A node
//   that is its own ancestor is an error.
// - Each primitive of each mesh a node holds becomes an object: triangles, strips and fans (as triangles);
//   points and lines have no surface to shade and are refused. Indices (8, 16 or 32 bits) must name a vertex
//   of POSITION. Sparse accessors and normalized integer components are read as the specification says.
//   Without NORMAL the triangles get flat normals (the specification's rule); a normal of zero length or not
//   finite takes the normal of the first triangle that uses its vertex.
// - Materials: the base colour factor is the diffuse colour. alphaMode OPAQUE gives alpha 1, BLEND the
//   factor's alpha, MASK alpha 1 where the factor's alpha reaches alphaCutoff and no object where it does
//   not (the surface is cut away everywhere). KHR_materials_transmission makes glass: alpha is (1 -
//   transmission) times the alpha above, refractive unless KHR_materials_ior sets ior 1. Approximated: the
//   refraction's strength is the command's, not the ior's, and the G-buffer keeps no per-pixel flag for it,
//   so once one material refracts all glass does; KHR_materials_volume tints the glass by Beer's law over its
//   thickness, attenuationColor ^ (thicknessFactor / attenuationDistance), in the shadow and the compose.
//   Roughness r gives the Phong exponent 2 / r^4 - 2 (within 1-255, the Blinn-Phong match of GGX's width;
//   refraction.hpp's dst_phong_power_of_roughness), from which `--rough-refraction on` reads r back to blur
//   what rough glass refracts (r up to 0.297 reads back as clear), and metallic m the specular intensity
//   0.04 + 0.96 m times (1 - r); metals keep their base colour as diffuse, since dstrans has no environment
//   light.
// - baseColorTexture: its image (PNG or JPEG, decoded only if a drawn material samples it, held to the
//   budget) becomes a scene texture, read at the primitive's TEXCOORD_<texCoord> (floats or normalized
//   unsigned integers; required where the material samples it), with its sampler's wrap modes. The
//   texels multiply the base colour as they are stored (sRGB values, like every dstrans colour: no
//   linear decoding); their alpha multiplies a BLEND material's, and a MASK material with a texture drops
//   the fragments whose alpha is below alphaCutoff per texel. A BLEND material whose factors are opaque
//   but whose texture has alpha is glass (alpha 254/255, what the G-buffer stores for any alpha that
//   close to 1, times the texel's). Approximated: every texture is read trilinearly with mip levels
//   whatever its sampler's filters, and resampled to the largest texture's size (at most 1024 a side)
//   to share one array (material_textures.hpp). KHR_texture_transform's offset, rotation and scale are
//   applied to the texture coordinates as they are read.
//   Other textures (normal, metallic-roughness, occlusion, emissive, transmission) are not read.
// - Cameras: the first perspective camera met walking the scene (its yfov, znear and zfar; an infinite zfar
//   becomes 1000 znear), looking down its node's -Z with +Y up. Without one, a camera 45 degrees wide frames
//   the scene's bounds from the front, above and right.
// - KHR_lights_punctual: directional, point and spot lights from their nodes (position, -Z direction),
//   colour, intensity and cones; every light casts shadows, as coloured glass shadows are the point of
//   dstrans. A point or spot light's range is its own or where intensity / d^2 falls to 1/255; its
//   intensity is scaled so dstrans's (1 - d / range)^2 falloff equals the inverse square at a quarter of
//   the range. A file without lights is lit by one directional light from above the camera's right.
// - extensionsRequired naming anything but the extensions above is refused, as is anything out of range.
#pragma once

#include <string>

#include <dstrans/result.hpp>
#include <dstrans/scene.hpp>

#include "scene_json.hpp"

namespace dstrans {

// Whether flatten() places every vertex of `s` at `transform` at a finite position with a finite,
// non-zero normal (a transform built from a file's numbers may overflow, or flatten a mesh).
bool finite_in_world(const shape& s, const glm::mat4& transform);

// Whether `path` names a glTF file by its extension (.gltf or .glb, any case).
bool is_gltf_path(const std::string& path);

// The scene in glTF file `path` (text .gltf with its buffers beside it, or binary .glb), or a sentence
// naming the file and the element that is wrong. The file and its geometry are held to `budget`.
result<scene> load_gltf(const std::string& path, const scene_budget& budget = {});

}  // namespace dstrans

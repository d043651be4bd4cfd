// A glTF file's JSON checked before tinygltf reads it: the JSON type the glTF 2.0 schema gives each
// property (tinygltf reads a property of the wrong type as if it were absent, so `"primitives": {...}`
// would load as a mesh with nothing in it, and `"index": -1` as no texture), and the extensions it requires.
//
//   if (auto wrong = dstrans::gltf_json_error(json_text, {"KHR_lights_punctual"}))
//     std::fprintf(stderr, "%s\n", wrong->c_str());   // "meshes[0].primitives: an array is needed"
//
// Checked: every property of the core specification, and of the extensions dstrans reads
// (KHR_lights_punctual, KHR_materials_transmission, KHR_materials_ior, KHR_materials_volume); every
// extension's value is an object. Property names the schema does not know are allowed, as glTF allows them.
#pragma once

#include <optional>
#include <set>
#include <string>

namespace dstrans {

// The first property of glTF JSON `text` whose type the schema does not allow, or the first extension in
// its extensionsRequired that is not in `readable`, as a sentence naming it; the same where the JSON nests
// deeper than a scene file may (json_input.hpp: tinygltf's parser would recurse once a level); nothing
// where all is well, or where the text is not JSON (tinygltf's parser says where).
std::optional<std::string> gltf_json_error(const std::string& text, const std::set<std::string>& readable);

// The JSON chunk of binary glTF `glb` (its first chunk), or nothing where the header is not one.
std::optional<std::string> glb_json(const std::string& glb);

}  // namespace dstrans

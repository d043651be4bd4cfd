// Implements gltf_types.hpp: the glTF 2.0 schema's property types as one table, walked with nlohmann-json.
#include "gltf_types.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "json_input.hpp"

namespace dstrans {

namespace {

using json = nlohmann::json;

// A property's type: "uint", "number", "string", "bool", "any"; "uint[]", "number[]", "string[]";
// "{uint}" (an object of indices, as attributes); "{uint}[]"; or a schema's name for an object of it,
// with "[]" after it for an array of them.
using schema = std::vector<std::pair<const char*, const char*>>;

// Every schema, by name; "<schema>.<extension>" is the extension's object on that schema's objects.
const std::map<std::string, schema>& schemas() {
  static const std::map<std::string, schema> s = {
      {"glTF", {{"asset", "asset"}, {"scene", "uint"}, {"scenes", "scene[]"}, {"nodes", "node[]"}, {"meshes", "mesh[]"},
                {"accessors", "accessor[]"}, {"bufferViews", "bufferView[]"}, {"buffers", "buffer[]"}, {"materials", "material[]"},
                {"textures", "texture[]"}, {"images", "image[]"}, {"samplers", "sampler[]"}, {"cameras", "camera[]"},
                {"skins", "skin[]"}, {"animations", "animation[]"}, {"extensionsUsed", "string[]"}, {"extensionsRequired", "string[]"}}},
      {"asset", {{"version", "string"}, {"generator", "string"}, {"copyright", "string"}, {"minVersion", "string"}}},
      {"scene", {{"nodes", "uint[]"}}},
      {"node", {{"camera", "uint"}, {"skin", "uint"}, {"mesh", "uint"}, {"children", "uint[]"}, {"matrix", "number[]"},
                {"rotation", "number[]"}, {"scale", "number[]"}, {"translation", "number[]"}, {"weights", "number[]"}}},
      {"mesh", {{"primitives", "primitive[]"}, {"weights", "number[]"}}},
      {"primitive", {{"attributes", "{uint}"}, {"indices", "uint"}, {"material", "uint"}, {"mode", "uint"}, {"targets", "{uint}[]"}}},
      {"accessor", {{"bufferView", "uint"}, {"byteOffset", "uint"}, {"componentType", "uint"}, {"normalized", "bool"}, {"count", "uint"},
                    {"type", "string"}, {"max", "number[]"}, {"min", "number[]"}, {"sparse", "sparse"}}},
      {"sparse", {{"count", "uint"}, {"indices", "sparseIndices"}, {"values", "sparseValues"}}},
      {"sparseIndices", {{"bufferView", "uint"}, {"byteOffset", "uint"}, {"componentType", "uint"}}},
      {"sparseValues", {{"bufferView", "uint"}, {"byteOffset", "uint"}}},
      {"bufferView", {{"buffer", "uint"}, {"byteOffset", "uint"}, {"byteLength", "uint"}, {"byteStride", "uint"}, {"target", "uint"}}},
      {"buffer", {{"uri", "string"}, {"byteLength", "uint"}}},
      {"material", {{"pbrMetallicRoughness", "pbrMetallicRoughness"}, {"normalTexture", "textureInfo"}, {"occlusionTexture", "textureInfo"},
                    {"emissiveTexture", "textureInfo"}, {"emissiveFactor", "number[]"}, {"alphaMode", "string"},
                    {"alphaCutoff", "number"}, {"doubleSided", "bool"}}},
      {"pbrMetallicRoughness", {{"baseColorFactor", "number[]"}, {"baseColorTexture", "textureInfo"}, {"metallicFactor", "number"},
                                {"roughnessFactor", "number"}, {"metallicRoughnessTexture", "textureInfo"}}},
      {"textureInfo", {{"index", "uint"}, {"texCoord", "uint"}, {"scale", "number"}, {"strength", "number"}}},
      {"texture", {{"sampler", "uint"}, {"source", "uint"}}},
      {"image", {{"uri", "string"}, {"mimeType", "string"}, {"bufferView", "uint"}}},
      {"sampler", {{"magFilter", "uint"}, {"minFilter", "uint"}, {"wrapS", "uint"}, {"wrapT", "uint"}}},
      {"camera", {{"type", "string"}, {"perspective", "perspective"}, {"orthographic", "orthographic"}}},
      {"perspective", {{"aspectRatio", "number"}, {"yfov", "number"}, {"zfar", "number"}, {"znear", "number"}}},
      {"orthographic", {{"xmag", "number"}, {"ymag", "number"}, {"zfar", "number"}, {"znear", "number"}}},
      {"skin", {{"inverseBindMatrices", "uint"}, {"skeleton", "uint"}, {"joints", "uint[]"}}},
      {"animation", {{"channels", "channel[]"}, {"samplers", "animationSampler[]"}}},
      {"channel", {{"sampler", "uint"}, {"target", "channelTarget"}}},
      {"channelTarget", {{"node", "uint"}, {"path", "string"}}},
      {"animationSampler", {{"input", "uint"}, {"interpolation", "string"}, {"output", "uint"}}},
      {"glTF.KHR_lights_punctual", {{"lights", "light[]"}}},
      {"light", {{"color", "number[]"}, {"intensity", "number"}, {"type", "string"}, {"range", "number"}, {"spot", "spot"}}},
      {"spot", {{"innerConeAngle", "number"}, {"outerConeAngle", "number"}}},
      {"node.KHR_lights_punctual", {{"light", "uint"}}},
      {"material.KHR_materials_transmission", {{"transmissionFactor", "number"}, {"transmissionTexture", "textureInfo"}}},
      {"material.KHR_materials_ior", {{"ior", "number"}}},
      {"material.KHR_materials_volume", {{"thicknessFactor", "number"}, {"thicknessTexture", "textureInfo"},
                                         {"attenuationDistance", "number"}, {"attenuationColor", "number[]"}}},
  };
  return s;
}

struct wrong_type {
  std::string message;
};

bool is_uint(const json& v) {
  if (v.is_number_unsigned()) return true;
  if (v.is_number_float()) {
    const double d = v.get<double>();
    return d >= 0.0 && d <= 4294967295.0 && std::floor(d) == d;
  }
  return false;
}

void check(const json& v, const std::string& type, const std::string& where);

// Object `v` of schema `name`: each property it knows, each extension's object, names and extras.
void check_object(const json& v, const std::string& name, const std::string& where) {
  if (!v.is_object()) throw wrong_type{where + ": an object is needed"};
  for (const auto& [key, type] : schemas().at(name))
    if (v.contains(key)) check(v.at(key), type, where + "." + key);
  if (v.contains("name") && !v.at("name").is_string()) throw wrong_type{where + ".name: a string is needed"};
  if (!v.contains("extensions")) return;
  const json& extensions = v.at("extensions");
  if (!extensions.is_object()) throw wrong_type{where + ".extensions: an object is needed"};
  for (const auto& [extension, value] : extensions.items()) {
    const std::string at = where + ".extensions." + key_excerpt(extension);
    if (schemas().count(name + "." + extension)) check_object(value, name + "." + extension, at);
    else if (!value.is_object()) throw wrong_type{at + ": an object is needed"};
  }
}

void check(const json& v, const std::string& type, const std::string& where) {
  if (type == "any") return;
  if (type.size() > 2 && type.compare(type.size() - 2, 2, "[]") == 0) {
    if (!v.is_array()) throw wrong_type{where + ": an array is needed"};
    for (std::size_t i = 0; i < v.size(); ++i) check(v[i], type.substr(0, type.size() - 2), where + "[" + std::to_string(i) + "]");
    return;
  }
  if (type == "uint") {
    if (!is_uint(v)) throw wrong_type{where + ": " + excerpt(v) + " is not an integer from 0"};
  } else if (type == "number") {
    if (!v.is_number()) throw wrong_type{where + ": " + excerpt(v) + " is not a number"};
  } else if (type == "string") {
    if (!v.is_string()) throw wrong_type{where + ": a string is needed"};
  } else if (type == "bool") {
    if (!v.is_boolean()) throw wrong_type{where + ": true or false is needed"};
  } else if (type == "{uint}") {
    if (!v.is_object()) throw wrong_type{where + ": an object is needed"};
    for (const auto& [key, value] : v.items()) check(value, "uint", where + "." + key_excerpt(key));
  } else {
    check_object(v, type, where);
  }
}

}  // namespace

std::optional<std::string> gltf_json_error(const std::string& text, const std::set<std::string>& readable) {
  json root;
  try {
    root = parse_bounded<json>(text, text.size());  // depth bounded: tinygltf's parser recurses once a level
  } catch (const json_too_big& e) {
    return "its JSON is " + e.message;
  } catch (const json::exception&) {
    return std::nullopt;  // tinygltf's parser says where
  }
  try {
    check_object(root, "glTF", "the file");
  } catch (const wrong_type& e) {
    // Paths name the root's properties alone ("meshes[0]"), as the rest of dstrans's glTF errors do.
    const std::string prefix = "the file.";
    return e.message.compare(0, prefix.size(), prefix) == 0 ? e.message.substr(prefix.size()) : e.message;
  }
  if (root.contains("extensionsRequired"))
    for (const json& e : root.at("extensionsRequired"))
      if (!readable.count(e.get<std::string>()))
        return "extensionsRequired: " + key_excerpt(e.get<std::string>()) + " is not an extension dstrans reads";
  return std::nullopt;
}

std::optional<std::string> glb_json(const std::string& glb) {
  auto word = [&](std::size_t at) {
    std::uint32_t w = 0;
    std::memcpy(&w, glb.data() + at, 4);
    return w;  // glb is little-endian, as every machine dstrans runs on
  };
  if (glb.size() < 20 || glb.compare(0, 4, "glTF") != 0 || word(16) != 0x4E4F534Au) return std::nullopt;
  const std::uint32_t length = word(12);
  if (length > glb.size() - 20) return std::nullopt;
  return glb.substr(20, length);
}

}  // namespace dstrans

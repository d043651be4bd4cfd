// Writes glTF files for the tests: accessors appended to one buffer (a data URI), meshes, nodes, and a
// whole dstrans scene as the glTF that scene_gltf.hpp reads back as the same scene.
//
//   gltf_doc d;
//   d.mesh({{"attributes", {{"POSITION", d.positions({0, 0, 0, 1, 0, 0, 0, 1, 0})}}}});
//   const std::string path = d.write("triangle");   // in the temporary folder
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <dstrans/scene.hpp>
#include <frame_output.hpp>

namespace dstrans {

// RFC 4648 base64 of `bytes`, padded.
inline std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t chunk = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < chunk; ++k) v |= std::uint32_t(std::uint8_t(bytes[i + k])) << (16 - 8 * k);
    for (std::size_t k = 0; k < 4; ++k) out += k <= chunk ? digits[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

// A glTF file being written: one buffer (a data URI), accessors appended to it.
struct gltf_doc {
  using json = nlohmann::json;
  json j = {{"asset", {{"version", "2.0"}}}};
  std::string bin;

  // An accessor of `values` as `type` ("VEC3", "SCALAR") with components of GL type `component`.
  template <class T>
  int add(const std::vector<T>& values, const char* type, int component) {
    while (bin.size() % 4) bin += '\0';
    const std::size_t offset = bin.size();
    bin.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
    const int width = std::string(type) == "VEC3" ? 3 : std::string(type) == "VEC2" ? 2 : 1;
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * sizeof(T)}});
    j["accessors"].push_back({{"bufferView", j["bufferViews"].size() - 1},
                              {"componentType", component},
                              {"count", values.size() / std::size_t(width)},
                              {"type", type}});
    return int(j["accessors"].size()) - 1;
  }
  int positions(const std::vector<float>& xyz) { return add(xyz, "VEC3", 5126); }
  int indices(const std::vector<std::uint32_t>& i) { return add(i, "SCALAR", 5125); }
  int texcoords(const std::vector<float>& st) { return add(st, "VEC2", 5126); }

  // Texture t as a PNG image (a data URI) with a sampler of its wrap modes; the glTF texture's index.
  int texture(const dstrans::texture& t) {
    const int modes[] = {10497, 33071, 33648};  // REPEAT, CLAMP_TO_EDGE, MIRRORED_REPEAT, as enum wrap
    j["images"].push_back({{"uri", "data:image/png;base64," + base64(render::png_bytes(render::image{t.width, t.height, t.rgba}))}});
    j["samplers"].push_back({{"wrapS", modes[int(t.wrap_s)]}, {"wrapT", modes[int(t.wrap_t)]}});
    j["textures"].push_back({{"source", j["images"].size() - 1}, {"sampler", j["samplers"].size() - 1}});
    return int(j["textures"].size()) - 1;
  }

  // A mesh of one primitive, held by a new root node with `node` properties; its index.
  int mesh(json primitive, json node = json::object()) {
    j["meshes"].push_back({{"primitives", json::array({primitive})}});
    node["mesh"] = j["meshes"].size() - 1;
    return root(node);
  }
  int root(json node) {
    j["nodes"].push_back(node);
    if (!j.contains("scenes")) j["scenes"] = json::array({{{"nodes", json::array()}}});
    j["scenes"][0]["nodes"].push_back(j["nodes"].size() - 1);
    return int(j["nodes"].size()) - 1;
  }

  // Written to a file named for `name` in the temporary folder; its path.
  std::string write(const std::string& name) {
    json out = j;
    if (bin.empty()) bin.assign(4, '\0');  // a buffer holds at least a byte
    out["buffers"] = json::array({{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
    const std::string path = (std::filesystem::temp_directory_path() / ("dstrans_" + std::to_string(getpid()) + "_" + name + ".gltf")).string();
    std::ofstream(path) << out.dump();
    return path;
  }
};


// Scene s as glTF: each object a mesh (positions, normals, indices, texture coordinates where it has them)
// on a node with its transform; each material's diffuse and alpha as its base colour (BLEND where
// transparent, MASK where alpha-tested; refractive glass as KHR_materials_transmission of 1 - alpha
// instead), its texture as a PNG base colour texture, rough and not metallic so that it has no specular;
// each light a KHR_lights_punctual light whose intensity scene_gltf.hpp maps back to the light's; the
// camera a perspective camera on a node looking from the view's position at its target.
inline gltf_doc from_scene(const scene& s) {
  using json = nlohmann::json;
  gltf_doc d;
  std::vector<int> textures;
  for (const texture& t : s.textures) textures.push_back(d.texture(t));
  for (const material& m : s.materials) {
    const bool masked = m.alpha_cutoff > 0.0f;
    json g = {{"alphaMode", masked ? "MASK" : m.alpha < 1.0f && !m.refractive ? "BLEND" : "OPAQUE"},
              {"pbrMetallicRoughness", {{"baseColorFactor", {m.diffuse.x, m.diffuse.y, m.diffuse.z, m.refractive ? 1.0f : m.alpha}},
                                        {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}};
    if (masked) g["alphaCutoff"] = m.alpha_cutoff;
    if (m.texture >= 0) g["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", textures.at(std::size_t(m.texture))}};
    if (m.refractive) g["extensions"]["KHR_materials_transmission"]["transmissionFactor"] = 1.0f - m.alpha;
    d.j["materials"].push_back(g);
  }
  auto floats = [](const std::vector<glm::vec3>& v) {
    std::vector<float> out;
    for (const glm::vec3& p : v) out.insert(out.end(), {p.x, p.y, p.z});
    return out;
  };
  auto matrix = [](const glm::mat4& m) { return std::vector<float>(glm::value_ptr(m), glm::value_ptr(m) + 16); };
  for (const object& o : s.objects) {
    json attributes = {{"POSITION", d.positions(floats(o.geometry.positions))}, {"NORMAL", d.positions(floats(o.geometry.normals))}};
    if (!o.geometry.uvs.empty()) {
      std::vector<float> st;
      for (const glm::vec2& uv : o.geometry.uvs) st.insert(st.end(), {uv.x, uv.y});
      attributes["TEXCOORD_0"] = d.texcoords(st);
    }
    d.mesh({{"attributes", attributes}, {"indices", d.indices(o.geometry.indices)}, {"material", o.material}},
           {{"matrix", matrix(o.transform)}});
  }
  d.j["cameras"] = {{{"type", "perspective"},
                     {"perspective", {{"yfov", glm::radians(s.view.fov_y)}, {"znear", s.view.near_plane}, {"zfar", s.view.far_plane}}}}};
  d.root({{"camera", 0}, {"matrix", matrix(glm::inverse(glm::lookAt(s.view.position, s.view.target, s.view.up())))}});
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    const light& l = s.lights[i];
    json g = {{"type", l.kind == light_kind::directional ? "directional" : l.kind == light_kind::point ? "point" : "spot"},
              {"color", {l.colour.x, l.colour.y, l.colour.z}},
              {"intensity", l.intensity}};
    if (l.kind != light_kind::directional) {
      g["range"] = l.range;
      g["intensity"] = l.intensity * 0.5625 * (0.25 * l.range) * (0.25 * l.range);  // scene_gltf.hpp's mapping, inverted
    }
    if (l.kind == light_kind::spot)
      g["spot"] = {{"innerConeAngle", glm::radians(l.inner_angle)}, {"outerConeAngle", glm::radians(l.outer_angle)}};
    d.j["extensions"]["KHR_lights_punctual"]["lights"].push_back(g);
    // A node at the light, its -z along the light's direction.
    const glm::vec3 up = std::fabs(l.direction.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    d.root({{"matrix", matrix(glm::inverse(glm::lookAt(l.position, l.position + l.direction, up)))},
            {"extensions", {{"KHR_lights_punctual", {{"light", i}}}}}});
  }
  return d;
}

}  // namespace dstrans

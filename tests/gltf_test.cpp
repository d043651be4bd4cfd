// glTF scenes: assimp's test models (valid ones load, broken ones name the element), and small files
// written here for each mapping of scene_gltf.hpp.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include <dstrans/scene.hpp>
#include <gltf_types.hpp>
#include <scene_gltf.hpp>
#include <scene_json.hpp>

#include "effect_scenes.hpp"
#include "gltf_writer.hpp"
#include "json_mutations.hpp"

using namespace dstrans;
using json = nlohmann::json;

namespace {

const std::string models = DSTRANS_GLTF_MODELS;  // assimp-testmodels' glTF2 folder

// One triangle in the plane z = 0, facing +z.
const std::vector<float> triangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

result<scene> load(gltf_doc& d, const std::string& name) {
  const std::string path = d.write(name);
  auto s = load_gltf(path);
  std::filesystem::remove(path);
  return s;
}

}  // namespace

TEST_CASE("a shape placed past the float range is told", "[scene][gltf]") {
  const shape tri{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}}, {0, 1, 2}, {}};
  CHECK(finite_in_world(tri, glm::mat4(1.0f)));
  CHECK(finite_in_world(tri, glm::scale(glm::mat4(1.0f), glm::vec3(1e12f))));
  CHECK_FALSE(finite_in_world(tri, glm::translate(glm::scale(glm::mat4(1.0f), glm::vec3(1e12f)), glm::vec3(1e30f))));
  CHECK_FALSE(finite_in_world(tri, glm::scale(glm::mat4(1.0f), glm::vec3(1e30f))));  // the normals' inverse overflows
  CHECK_FALSE(finite_in_world(tri, glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, 1.0f, 0.0f))));  // flattened: no normal
}

TEST_CASE("glTF files are told by their extension", "[scene][gltf]") {
  CHECK(is_gltf_path("a/b.gltf"));
  CHECK(is_gltf_path("B.GLB"));
  CHECK_FALSE(is_gltf_path("scene.json"));
  CHECK_FALSE(is_gltf_path("gltf"));
}

TEST_CASE("assimp's glTF test models: the box loads the same from .gltf, .glb and embedded", "[scene][gltf]") {
  INFO("assimp's glTF models in " << models << " (Debian's assimp-testmodels; make test installs it)");
  REQUIRE(std::filesystem::is_directory(models));
  std::vector<scene> boxes;
  for (const char* file : {"BoxTextured-glTF/BoxTextured.gltf", "BoxTextured-glTF-Binary/BoxTextured.glb",
                           "BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
    auto s = load_scene(models + "/" + file);  // load_scene takes glTF by its extension
    INFO(file << ": " << (s ? "" : s.error()));
    REQUIRE(s);
    REQUIRE(s->objects.size() == 1);
    CHECK(s->objects[0].geometry.triangles() == 12);
    const scene_mesh m = flatten(*s);
    for (const glm::vec3& p : m.positions)
      for (int c = 0; c < 3; ++c) CHECK(std::fabs(p[c]) == Approx(0.5f));
    for (const glm::vec3& n : m.normals) CHECK(glm::length(n) == Approx(1.0f));
    CHECK(s->lights.size() == 1);  // the default light of a file without lights
    CHECK(s->lights[0].shadows);
    // CesiumLogoFlat.png (a palette PNG) as RGBA, read at TEXCOORD_0.
    REQUIRE(s->textures.size() == 1);
    CHECK(s->textures[0].width == 211);
    CHECK(s->textures[0].valid());
    CHECK(s->materials[0].texture == 0);
    CHECK(m.uvs.size() == m.positions.size());
    boxes.push_back(*s);
  }
  // assimp's .gltf copy samples it mirrored along s and clamped along t; the other two repeat.
  CHECK(boxes[0].textures[0].wrap_s == wrap::mirror);
  CHECK(boxes[0].textures[0].wrap_t == wrap::clamp);
  CHECK(boxes[1].textures[0].wrap_s == wrap::repeat);
  for (std::size_t i = 1; i < boxes.size(); ++i) {
    CHECK(flatten(boxes[i]).positions == flatten(boxes[0]).positions);
    CHECK(flatten(boxes[i]).uvs == flatten(boxes[0]).uvs);
    CHECK(boxes[i].textures[0].rgba == boxes[0].textures[0].rgba);
    CHECK(boxes[i].materials[0].diffuse == boxes[0].materials[0].diffuse);
  }
  // KHR_texture_transform (used, not required): materials 0 and 2 move the same coordinates by (0.5, 0) and (0.5, 0.5).
  auto moved = load_scene(models + "/textureTransform/TextureTransformTest.gltf");
  INFO((moved ? "" : moved.error()));
  REQUIRE(moved);
  CHECK(moved->textures.size() == 5);
  auto with_material = [&](std::uint32_t m) -> const shape& {
    const auto o = std::find_if(moved->objects.begin(), moved->objects.end(), [&](const object& x) { return x.material == m; });
    REQUIRE(o != moved->objects.end());
    return o->geometry;
  };
  const shape &u = with_material(0), &uv = with_material(2);  // "Offset U" and "Offset UV"
  REQUIRE(u.uvs.size() == 6);  // without normals: three vertices a triangle (flat)
  REQUIRE(uv.uvs.size() == 6);
  for (std::size_t v = 0; v < 6; ++v) CHECK(glm::distance(uv.uvs[v], u.uvs[v] + glm::vec2(0.0f, 0.5f)) < 1e-6f);
  // Larger valid models: many nodes and meshes, a camera, strips and fans.
  for (const char* file : {"2CylinderEngine-glTF-Binary/2CylinderEngine.glb", "cameras/Cameras.gltf", "ClearCoat-glTF/ClearCoatTest.gltf",
                           "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_05.gltf",
                           "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_06.gltf", "BoxBadNormals-glTF-Binary/BoxBadNormals.glb"}) {
    auto s = load_scene(models + "/" + file);
    INFO(file << ": " << (s ? "" : s.error()));
    REQUIRE(s);
    CHECK_FALSE(s->objects.empty());
    for (const glm::vec3& n : flatten(*s).normals) CHECK(glm::length(n) == Approx(1.0f).margin(1e-4));
  }
}

TEST_CASE("assimp's broken glTF test models get an error naming the file and the element", "[scene][gltf][hostile]") {
  struct broken {
    const char* file;
    const char* says;
  };
  for (const broken& b : {
           broken{"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", ": meshes[0].primitives[0].attributes.POSITION[0]: not a finite position"},
           broken{"IndexOutOfRange/IndexOutOfRange.gltf", ": meshes[0].primitives[0].indices[0]: 255 is past the 24 vertices of attributes.POSITION"},
           broken{"IndexOutOfRange/AllIndicesOutOfRange.gltf", ": meshes[0].primitives[0].indices[0]: 65535 is past the 24 vertices"},
           broken{"IncorrectVertexArrays/Cube.gltf", ": meshes[1].primitives[0]: 35 vertices do not make whole triangles"},
           broken{"MissingBin/BoxTextured.gltf", "BoxTextured0.bin"},
           broken{"RecursiveNodes/RecursiveNodes.gltf", ": nodes[0]: the node is its own ancestor"},
           broken{"SchemaFailures/sceneWrongType.gltf", ": scene: the string \"hello\" is not an integer from 0"},
           broken{"TestNoRootNode/NoScene.gltf", ": scene: 0 is not one of the 0 there are"},
           broken{"TestNoRootNode/SceneWithoutNodes.gltf", ": no triangles to draw in its scene"},
           broken{"draco/2CylinderEngine.gltf", ": extensionsRequired: KHR_draco_mesh_compression is not an extension dstrans reads"},
           broken{"wrongTypes/badArray.gltf", ": meshes[0].primitives: an array is needed"},
           broken{"wrongTypes/badExtension.gltf", ": materials[0].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform: an object is needed"},
           broken{"wrongTypes/badNumber.gltf", ": materials[0].normalTexture.scale: the string \"not a number\" is not a number"},
           broken{"wrongTypes/badObject.gltf", ": materials[0].pbrMetallicRoughness: an object is needed"},
           broken{"wrongTypes/badString.gltf", ": scenes[0].name: a string is needed"},
           broken{"wrongTypes/badUint.gltf", ".baseColorTexture.index: -1 is not an integer from 0"},
           broken{"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_01.gltf",
                  ": meshes[0].primitives[0].mode: 1 (points or lines) has no surface to shade"}}) {
    const std::string path = models + "/" + b.file;
    auto s = load_scene(path);
    INFO(b.file);
    REQUIRE_FALSE(s);
    CHECK_THAT(s.error(), Catch::StartsWith(path + ": ") && Catch::Contains(b.says));
  }
  auto zero = load_gltf("/dev/zero");
  REQUIRE_FALSE(zero);
  CHECK(zero.error() == "/dev/zero: not a plain file, so not read as a glTF file");
}

TEST_CASE("glTF geometry: node transforms, strips and fans, flat and repaired normals, sparse and normalized accessors",
          "[scene][gltf]") {
  gltf_doc d;
  const int p = d.positions(triangle);
  // TRS: scaled by 2, turned 90 degrees about +y, moved by (1, 2, 3).
  d.mesh({{"attributes", {{"POSITION", p}}}},
         {{"translation", {1, 2, 3}}, {"rotation", {0, std::sqrt(0.5), 0, std::sqrt(0.5)}}, {"scale", {2, 2, 2}}});
  // A strip and a fan of four vertices: two triangles each, wound as the first.
  const int quad = d.positions({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
  d.mesh({{"attributes", {{"POSITION", quad}}}, {"mode", 5}});
  d.mesh({{"attributes", {{"POSITION", quad}}}, {"mode", 6}, {"indices", d.indices({0, 1, 3, 2})}});
  // A zero normal takes its triangle's; a sparse accessor replaces vertex 2 with (0, 2, 0).
  const int normals = d.positions({0, 0, 1, 0, 0, 0, 0, 0, 1});
  d.mesh({{"attributes", {{"POSITION", p}, {"NORMAL", normals}}}});
  json sparse = d.j["accessors"][std::size_t(p)];
  const int rows = d.indices({2}), values = d.positions({0, 2, 0});
  sparse["sparse"] = {{"count", 1},
                      {"indices", {{"bufferView", d.j["accessors"][std::size_t(rows)]["bufferView"]}, {"componentType", 5125}}},
                      {"values", {{"bufferView", d.j["accessors"][std::size_t(values)]["bufferView"]}}}};
  d.j["accessors"].push_back(sparse);
  d.mesh({{"attributes", {{"POSITION", int(d.j["accessors"].size()) - 1}}}});
  // Normalized unsigned bytes: 255 is 1.
  const int bytes = d.add(std::vector<std::uint8_t>{0, 0, 0, 0, 255, 0, 0, 0, 0, 255, 0, 0}, "VEC3", 5121);
  d.j["accessors"][std::size_t(bytes)]["normalized"] = true;
  d.j["accessors"][std::size_t(bytes)]["count"] = 3;
  d.j["bufferViews"][d.j["accessors"][std::size_t(bytes)]["bufferView"].get<std::size_t>()]["byteStride"] = 4;
  d.mesh({{"attributes", {{"POSITION", bytes}}}});
  auto s = load(d, "geometry");
  INFO((s ? "" : s.error()));
  REQUIRE(s);
  REQUIRE(s->objects.size() == 6);
  auto world = [&](std::size_t o, std::size_t v) { return glm::vec3(s->objects[o].transform * glm::vec4(s->objects[o].geometry.positions[v], 1.0f)); };
  // Without NORMAL: flat, the face's normal (here turned to +x), three vertices of its own per triangle.
  CHECK(glm::distance(world(0, 1), glm::vec3(1, 2, 1)) < 1e-5f);  // (1,0,0) scaled to 2, turned to -z... then moved
  CHECK(glm::distance(world(0, 2), glm::vec3(1, 4, 3)) < 1e-5f);
  CHECK(glm::distance(glm::mat3(s->objects[0].transform) * s->objects[0].geometry.normals[0], glm::vec3(2, 0, 0)) < 1e-5f);
  for (std::size_t o : {std::size_t(1), std::size_t(2)}) {
    const shape& g = s->objects[o].geometry;
    REQUIRE(g.triangles() == 2);
    for (std::size_t t = 0; t < 6; t += 3) {
      const glm::vec3 a = g.positions[g.indices[t]], b = g.positions[g.indices[t + 1]], c = g.positions[g.indices[t + 2]];
      CHECK(glm::cross(b - a, c - a).z > 0.0f);  // every triangle faces +z, as the first
    }
  }
  CHECK(s->objects[3].geometry.normals[1] == glm::vec3(0, 0, 1));
  CHECK(s->objects[4].geometry.positions[2] == glm::vec3(0, 2, 0));
  CHECK(s->objects[4].geometry.positions[1] == glm::vec3(1, 0, 0));
  CHECK(s->objects[5].geometry.positions[1] == glm::vec3(1, 0, 0));
  CHECK(s->objects[5].geometry.positions[2] == glm::vec3(0, 1, 0));
  // A node scaled to 0 is hidden, as glTF hides one: nothing of it is drawn.
  d.mesh({{"attributes", {{"POSITION", p}}}}, {{"scale", {0, 1, 1}}});
  auto hidden = load(d, "hidden");
  REQUIRE(hidden);
  CHECK(hidden->objects.size() == 6);
}

TEST_CASE("glTF materials: alpha modes, transmission as glass, ior, Beer's law, roughness and metallic", "[scene][gltf]") {
  gltf_doc d;
  const int p = d.positions(triangle);
  auto add = [&](json m) {
    d.j["materials"].push_back(m);
    d.mesh({{"attributes", {{"POSITION", p}}}, {"material", d.j["materials"].size() - 1}});
  };
  add({{"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.4, 0.6, 0.5}}}}});  // OPAQUE: alpha 1
  add({{"alphaMode", "BLEND"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.4, 0.6, 0.5}}, {"roughnessFactor", 0.5}, {"metallicFactor", 0.0}}}});
  add({{"alphaMode", "MASK"}, {"alphaCutoff", 0.6}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 0.5}}}}});  // cut away
  add({{"alphaMode", "MASK"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 0.5}}}}});  // kept, opaque
  add({{"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.9, 0.9, 1}}, {"roughnessFactor", 0.0}, {"metallicFactor", 1.0}}},
       {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 0.75}}},
                       {"KHR_materials_volume", {{"thicknessFactor", 0.5}, {"attenuationDistance", 0.25}, {"attenuationColor", {0.5, 1.0, 0.25}}}}}}});
  add({{"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}, {"KHR_materials_ior", {{"ior", 1.0}}}}}});
  auto s = load(d, "materials");
  INFO((s ? "" : s.error()));
  REQUIRE(s);
  REQUIRE(s->objects.size() == 5);  // the cut-away one is not drawn
  auto of = [&](std::size_t o) { return s->materials[s->objects[o].material]; };
  CHECK(of(0).alpha == 1.0f);
  CHECK(of(0).diffuse == glm::vec3(0.2f, 0.4f, 0.6f));
  CHECK(of(1).alpha == 0.5f);
  CHECK(of(1).transparent());
  CHECK(of(1).spec_power == Approx(2.0f / 0.0625f - 2.0f));  // 2 / r^4 - 2
  CHECK(of(1).spec_intensity == Approx(0.04f * 0.5f));
  CHECK(of(2).alpha == 1.0f);
  CHECK(of(3).alpha == Approx(0.25f));  // 1 - transmission
  CHECK(of(3).refractive);
  CHECK(of(3).spec_power == 255.0f);
  CHECK(of(3).spec_intensity == Approx(1.0f));
  // attenuationColor ^ (0.5 / 0.25): squared.
  CHECK(of(3).diffuse.x == Approx(0.9f * 0.25f));
  CHECK(of(3).diffuse.y == Approx(0.9f));
  CHECK(of(3).diffuse.z == Approx(0.9f * 0.0625f));
  CHECK(of(4).alpha == 0.0f);
  CHECK_FALSE(of(4).refractive);  // ior 1 bends nothing
}

TEST_CASE("glTF cameras and punctual lights, and the defaults of a file without them", "[scene][gltf]") {
  gltf_doc d;
  d.mesh({{"attributes", {{"POSITION", d.positions(triangle)}}}});
  d.j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.01}, {"zfar", 1e6}}}}};
  // Looking down -z from (0.5, 0.5, 4): the planes close in on the triangle's bounding sphere.
  d.root({{"camera", 0}, {"translation", {0.5, 0.5, 4}}});
  d.j["extensionsUsed"] = {"KHR_lights_punctual"};
  d.j["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "directional"}, {"color", {1, 0.5, 0.25}}, {"intensity", 3}},
      {{"type", "point"}, {"intensity", 16}, {"range", 8}},
      {{"type", "spot"}, {"intensity", 1}, {"spot", {{"innerConeAngle", 0.25}, {"outerConeAngle", 0.5}}}}};
  // Pointing down: a turn of -90 degrees about x takes -z to -y.
  const json down = {std::sin(-0.25 * M_PI), 0, 0, std::cos(-0.25 * M_PI)};
  d.root({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}, {"rotation", down}});
  d.root({{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}, {"translation", {1, 2, 3}}});
  d.root({{"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}, {"rotation", down}, {"translation", {0, 5, 0}}});
  auto s = load(d, "views");
  INFO((s ? "" : s.error()));
  REQUIRE(s);
  CHECK(s->view.position == glm::vec3(0.5f, 0.5f, 4.0f));
  CHECK(glm::distance(s->view.target, glm::vec3(0.5f, 0.5f, 3.0f)) < 1e-6f);
  CHECK(s->view.fov_y == Approx(glm::degrees(0.5f)));
  const float radius = 0.5f * std::sqrt(2.0f), distance = 4.0f;  // the triangle's bounds are the unit square
  CHECK(s->view.far_plane == Approx(distance + 1.01f * radius));
  CHECK(s->view.near_plane == Approx(distance - 1.01f * radius));
  REQUIRE(s->lights.size() == 3);
  const light &sun = s->lights[0], &lamp = s->lights[1], &spot = s->lights[2];
  CHECK(sun.kind == light_kind::directional);
  CHECK(glm::distance(sun.direction, glm::vec3(0, -1, 0)) < 1e-5f);
  CHECK(sun.colour == glm::vec3(1.0f, 0.5f, 0.25f));
  CHECK(sun.intensity == 3.0f);
  CHECK(sun.shadows);
  CHECK(lamp.kind == light_kind::point);
  CHECK(lamp.position == glm::vec3(1, 2, 3));
  CHECK(lamp.range == 8.0f);
  // At a quarter of the range the falloffs agree: 16 / 2^2 = 4.
  CHECK(lamp.intensity * std::pow(1.0f - 0.25f, 2.0f) == Approx(16.0f / 4.0f));
  CHECK(spot.kind == light_kind::spot);
  CHECK(spot.range == Approx(std::sqrt(255.0f)));  // where 1 / d^2 is 1/255
  CHECK(spot.inner_angle == Approx(glm::degrees(0.25f)));
  CHECK(spot.outer_angle == Approx(glm::degrees(0.5f)));
  CHECK(glm::distance(spot.position, glm::vec3(0, 5, 0)) < 1e-5f);
  // Without a camera or lights: one framing the bounds, and a directional light casting shadows.
  gltf_doc bare;
  bare.mesh({{"attributes", {{"POSITION", bare.positions(triangle)}}}});
  auto b = load(bare, "bare");
  REQUIRE(b);
  CHECK(glm::distance(b->view.target, glm::vec3(0.5f, 0.5f, 0.0f)) < 1e-6f);
  CHECK(b->view.fov_y == 45.0f);
  CHECK(glm::distance(b->view.position, b->view.target) > 1.0f);
  REQUIRE(b->lights.size() == 1);
  CHECK(b->lights[0].kind == light_kind::directional);
  CHECK(b->lights[0].direction.y < 0.0f);
  CHECK(b->lights[0].shadows);
}

TEST_CASE("glTF base colour textures: coordinates, samplers, MASK per texel, BLEND by texel alpha, transforms", "[scene][gltf]") {
  gltf_doc d;
  const int p = d.positions(triangle), st = d.texcoords({0, 0, 1, 0, 0, 1}), st1 = d.texcoords({0.5, 0.5, 0.5, 0.5, 0.5, 0.5});
  texture opaque = testing::chequer(2, 1, {255, 0, 0, 255}, {0, 255, 0, 255}), translucent = opaque;
  translucent.rgba[3] = 100;
  translucent.wrap_s = wrap::clamp;
  translucent.wrap_t = wrap::mirror;
  const int t0 = d.texture(opaque), t1 = d.texture(translucent);
  d.j["images"].push_back({{"uri", "data:image/png;base64,bm90IGEgUE5H"}});  // "not a PNG", which no material samples
  auto add = [&](json m, json attributes) {
    d.j["materials"].push_back(m);
    attributes["POSITION"] = p;
    d.mesh({{"attributes", attributes}, {"material", d.j["materials"].size() - 1}});
  };
  auto textured = [&](int t, json more = json::object()) {
    json info = {{"index", t}};
    info.update(more);
    return json{{"baseColorFactor", {0.5, 1, 1, 0.8}}, {"baseColorTexture", info}};
  };
  add({{"pbrMetallicRoughness", textured(t0)}}, {{"TEXCOORD_0", st}});                                       // OPAQUE
  add({{"alphaMode", "MASK"}, {"alphaCutoff", 0.25}, {"pbrMetallicRoughness", textured(t0)}}, {{"TEXCOORD_0", st}});
  add({{"alphaMode", "BLEND"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", t1}}}}}}, {{"TEXCOORD_0", st}});
  add({{"alphaMode", "BLEND"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", t0}}}}}}, {{"TEXCOORD_0", st}});
  add({{"pbrMetallicRoughness", textured(t0, {{"texCoord", 1}})}}, {{"TEXCOORD_0", st}, {"TEXCOORD_1", st1}});
  add({{"pbrMetallicRoughness", textured(t0, {{"extensions", {{"KHR_texture_transform", {{"offset", {1, 2}}, {"rotation", M_PI / 2}, {"scale", {2, 3}}}}}}})}},
      {{"TEXCOORD_0", st}});
  auto s = load(d, "textures");
  INFO((s ? "" : s.error()));
  REQUIRE(s);
  REQUIRE(s->objects.size() == 6);
  REQUIRE(s->textures.size() == 2);  // each glTF texture once, however many materials sample it
  CHECK(s->textures[0].rgba == opaque.rgba);
  CHECK(s->textures[1].rgba == translucent.rgba);
  CHECK(s->textures[1].wrap_s == wrap::clamp);
  CHECK(s->textures[1].wrap_t == wrap::mirror);
  auto of = [&](std::size_t o) { return s->materials[s->objects[o].material]; };
  CHECK(of(0).texture == 0);
  CHECK(of(0).alpha == 1.0f);  // OPAQUE: neither the factor's alpha nor the texels'
  CHECK(of(0).alpha_cutoff == 0.0f);
  CHECK(of(0).diffuse == glm::vec3(0.5f, 1.0f, 1.0f));
  CHECK(s->objects[0].geometry.uvs == std::vector<glm::vec2>{{0, 0}, {1, 0}, {0, 1}});
  CHECK(of(1).alpha_cutoff == 0.25f);  // MASK: tested per texel, the factor's alpha with the texel's
  CHECK(of(1).alpha == Approx(0.8f));
  CHECK_FALSE(of(1).transparent());
  CHECK(of(2).texture == 1);
  CHECK(of(2).alpha == Approx(254.0f / 255.0f));  // BLEND, opaque factors, translucent texels: glass
  CHECK(of(2).transparent());
  CHECK(of(3).alpha == 1.0f);  // BLEND over opaque texels and factors: nothing to blend
  CHECK(s->objects[4].geometry.uvs == std::vector<glm::vec2>(3, glm::vec2(0.5f)));  // texCoord 1
  // T R S: (1, 0) scaled (2, 0), turned by 90 degrees as the extension turns (0, -2), moved (1, 0).
  const std::vector<glm::vec2>& turned = s->objects[5].geometry.uvs;
  REQUIRE(turned.size() == 3);
  CHECK(glm::distance(turned[0], glm::vec2(1, 2)) < 1e-6f);
  CHECK(glm::distance(turned[1], glm::vec2(1, 0)) < 1e-6f);
  CHECK(glm::distance(turned[2], glm::vec2(4, 2)) < 1e-6f);
}

TEST_CASE("bad glTF elements get an error naming them, never a crash", "[scene][gltf][hostile]") {
  struct bad {
    std::function<void(gltf_doc&)> edit;
    std::string says;
  };
  auto tri = [](gltf_doc& d) { return d.mesh({{"attributes", {{"POSITION", d.positions(triangle)}}}}); };
  // A triangle whose material samples a texture of one texel, with texture coordinates `st` (none: empty).
  const std::vector<float> st = {0, 0, 1, 0, 0, 1};
  auto textured = [](gltf_doc& d, const std::vector<float>& coordinates) {
    d.j["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", d.texture(testing::chequer(1, 1, {}, {}))}}}}}}};
    json attributes = {{"POSITION", d.positions(triangle)}};
    if (!coordinates.empty()) attributes["TEXCOORD_0"] = d.texcoords(coordinates);
    d.mesh({{"attributes", attributes}, {"material", 0}});
  };
  for (const bad& b : std::vector<bad>{
           {[&](gltf_doc& d) { d.mesh({{"attributes", {{"POSITION", 7}}}}); }, "meshes[0].primitives[0].attributes.POSITION: 7 is not one of the 0 there are"},
           {[&](gltf_doc& d) { d.mesh({{"attributes", {{"POSITION", d.positions({0, 0, 0, NAN, 0, 0, 0, 1, 0})}}}}); },
            "meshes[0].primitives[0].attributes.POSITION[1]: not a finite position"},
           {[&](gltf_doc& d) { d.mesh({{"attributes", {{"POSITION", d.indices({0, 1, 2})}}}}); }, "accessors[0].type: 3 components a vertex are needed"},
           {[&](gltf_doc& d) {
              tri(d);
              d.j["accessors"][0]["count"] = 1000;
            },
            "accessors[0]: 1000 elements from byte 0 do not fit the 36 bytes of bufferViews[0]"},
           {[&](gltf_doc& d) {
              tri(d);
              d.j["accessors"][0]["byteOffset"] = 18446744073709551600ull;  // would wrap a sum of offsets
            },
            "accessors[0]: 3 elements from byte 18446744073709551600 do not fit the 36 bytes of bufferViews[0]"},
           {[&](gltf_doc& d) {
              tri(d);
              d.j["bufferViews"][0]["byteStride"] = 1000000;  // tinygltf refuses it first, we would too
            },
            "byteStride"},
           {[&](gltf_doc& d) {
              tri(d);
              d.j["bufferViews"][0]["byteStride"] = 8;
            },
            "bufferViews[0].byteStride: 8 is not from 12 to 252"},
           {[&](gltf_doc& d) {  // no buffer view: zeros, as many as it names
              d.j["accessors"] = {{{"componentType", 5126}, {"count", 4000000000ull}, {"type", "VEC3"}}};
              d.mesh({{"attributes", {{"POSITION", 0}}}});
            },
            "accessors[0].count: 4000000000 elements are more than the budget holds"},
           {[&](gltf_doc& d) {
              tri(d);
              d.j["bufferViews"][0]["byteLength"] = 1 << 20;
            },
            "bufferViews[0]: bytes 0 to 1048576 are past the 36 of buffers[0]"},
           {[&](gltf_doc& d) {
              tri(d);
              d.j["meshes"][0]["primitives"][0]["material"] = 3;
            },
            "meshes[0].primitives[0].material: 3 is not one of the 0 there are"},
           {[&](gltf_doc& d) {
              tri(d);
              d.j["nodes"][0]["matrix"] = {1, 0, 0};
            },
            "nodes[0].matrix: 16 numbers are needed"},
           {[&](gltf_doc& d) {
              tri(d);
              d.j["nodes"][0]["children"] = {0};
            },
            "nodes[0]: the node is its own ancestor"},
           {[&](gltf_doc& d) {
              tri(d);
              d.j["nodes"][0]["scale"] = {1e39, 1, 1};
            },
            "nodes[0].scale[0]: not a finite float"},
           {[&](gltf_doc& d) {  // each scale a float, their product past the range
              tri(d);
              d.j["nodes"][0]["scale"] = {1e30, 1, 1};
              d.j["nodes"].push_back({{"scale", {1e30, 1, 1}}, {"children", {0}}});
              d.j["scenes"][0]["nodes"] = {1};
            },
            "nodes[0]: its transform is past the float range"},
           {[&](gltf_doc& d) {
              tri(d);
              d.j["nodes"][0]["translation"] = {3e38, 0, 0};
              d.j["nodes"].push_back({{"translation", {3e38, 0, 0}}, {"children", {0}}});
              d.j["scenes"][0]["nodes"] = {1};
            },
            "nodes[0]: its transform takes meshes[0].primitives[0] past the float range"},
           {[&](gltf_doc& d) {
              tri(d);
              d.j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 1}, {"znear", 0.1}}}}};
              d.root({{"translation", {3e38, 0, 0}}, {"children", {2}}});
              d.j["nodes"].push_back({{"camera", 0}, {"translation", {3e38, 0, 0}}});
            },
            "nodes[2].camera: its node's transform is past the float range"},
           {[&](gltf_doc& d) {
              tri(d);
              d.j["extensionsRequired"] = {"KHR_texture_basisu"};
            },
            "extensionsRequired: KHR_texture_basisu is not an extension dstrans reads"},
           {[&](gltf_doc& d) {
              d.j["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 5}}}}}}};
              d.mesh({{"attributes", {{"POSITION", d.positions(triangle)}}}, {"material", 0}});
            },
            "materials[0].pbrMetallicRoughness.baseColorTexture.index: 5 is not one of the 0 there are"},
           {[&](gltf_doc& d) { textured(d, {}); }, "meshes[0].primitives[0].attributes.TEXCOORD_0: absent, and its material's baseColorTexture reads it"},
           {[&](gltf_doc& d) { textured(d, {0, 0, 1, 0}); }, "meshes[0].primitives[0].attributes.TEXCOORD_0: 2 coordinates for 3 positions"},
           {[&](gltf_doc& d) { textured(d, {0, 0, 1, 0, NAN, 1}); }, "meshes[0].primitives[0].attributes.TEXCOORD_0[2]: not finite"},
           {[&](gltf_doc& d) {
              textured(d, st);
              d.j["images"][0]["uri"] = "data:image/png;base64,bm90IGEgUE5H";  // "not a PNG"
            },
            "images[0]: not an image that can be read"},
           {[&](gltf_doc& d) {
              textured(d, st);
              d.j["images"][0]["uri"] = "no_such_texture.png";
            },
            "no_such_texture.png"},
           {[&](gltf_doc& d) {
              textured(d, st);
              d.j["textures"][0]["source"] = 3;
            },
            "textures[0].source: 3 is not one of the 1 there are"},
           {[&](gltf_doc& d) {
              textured(d, st);
              d.j["samplers"][0]["wrapS"] = 5;
            },
            "samplers[0].wrapS: 5 is not 10497 (REPEAT), 33071 (CLAMP_TO_EDGE) or 33648 (MIRRORED_REPEAT)"},
           {[&](gltf_doc& d) {
              tri(d);
              d.j["materials"] = {{{"alphaMode", "CLEAR"}}};
              d.j["meshes"][0]["primitives"][0]["material"] = 0;
            },
            "materials[0].alphaMode: \"CLEAR\" is not OPAQUE, MASK or BLEND"},
           {[&](gltf_doc& d) {
              tri(d);
              d.j["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "spot"}, {"spot", {{"innerConeAngle", 1}, {"outerConeAngle", 0.5}}}}};
              d.root({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
            },
            "lights[0].spot: 0 <= innerConeAngle < outerConeAngle <= pi/2 is needed"},
           {[&](gltf_doc& d) {
              tri(d);
              d.root({{"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
            },
            "nodes[1].extensions.KHR_lights_punctual.light: 2 is not one of the 0 there are"},
           {[&](gltf_doc& d) {
              tri(d);
              d.j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0}, {"znear", 0.1}}}}};
              d.root({{"camera", 0}});
            },
            "cameras[0].perspective: 0 < yfov < pi and 0 < znear < zfar (or zfar absent) are needed"},
           {[&](gltf_doc& d) { d.j["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", "zero"}}}}}}}}; },
            "meshes[0].primitives[0].attributes.POSITION: the string \"zero\" is not an integer from 0"},
       }) {
    gltf_doc d;
    b.edit(d);
    auto s = load(d, "bad");
    INFO(b.says);
    REQUIRE_FALSE(s);
    CHECK_THAT(s.error(), Catch::Contains(b.says));
  }
  // The budget, checked as the geometry grows: a mesh held by many nodes.
  gltf_doc many;
  tri(many);
  for (int i = 0; i < 2000; ++i) many.root({{"mesh", 0}});
  const std::string path = many.write("many");
  scene_budget small;
  small.bytes = 1000 * 3 * bytes_per_vertex;
  auto refused = load_gltf(path, small);
  std::filesystem::remove(path);
  REQUIRE_FALSE(refused);
  CHECK_THAT(refused.error(), Catch::Contains("the scene would take about") && Catch::Contains("(--budget MIB raises it)"));
  // Not a glTF file at all, and a truncated binary one.
  const std::string text = (std::filesystem::temp_directory_path() / ("dstrans_" + std::to_string(getpid()) + "_text.gltf")).string();
  std::ofstream(text) << "{\"asset\": ";
  auto cut = load_gltf(text);
  std::filesystem::remove(text);
  REQUIRE_FALSE(cut);
  CHECK_THAT(cut.error(), Catch::StartsWith(text + ": "));
  std::string glb;
  {
    std::ifstream in(models + "/BoxTextured-glTF-Binary/BoxTextured.glb", std::ios::binary);
    glb.assign(std::istreambuf_iterator<char>(in), {});
  }
  REQUIRE(glb_json(glb));
  const std::string half = (std::filesystem::temp_directory_path() / ("dstrans_" + std::to_string(getpid()) + "_half.glb")).string();
  std::ofstream(half, std::ios::binary) << glb.substr(0, glb.size() / 2);
  auto truncated = load_gltf(half);
  std::filesystem::remove(half);
  REQUIRE_FALSE(truncated);
  CHECK_THAT(truncated.error(), Catch::StartsWith(half + ": "));
  CHECK_FALSE(glb_json("glTF"));
}

TEST_CASE("the glTF schema's types: what tinygltf would read as absent is an error", "[scene][gltf]") {
  CHECK_FALSE(gltf_json_error(R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 0, "matrix": [1]}]})", {}));
  CHECK(gltf_json_error(R"({"asset": {"version": 2}})", {}) == std::string("asset.version: a string is needed"));
  CHECK(gltf_json_error(R"({"nodes": [{"children": [0, -1]}]})", {}) == std::string("nodes[0].children[1]: -1 is not an integer from 0"));
  CHECK(gltf_json_error(R"({"nodes": [{"mesh": 1.5}]})", {}) == std::string("nodes[0].mesh: 1.5 is not an integer from 0"));
  CHECK_FALSE(gltf_json_error(R"({"nodes": [{"mesh": 1.0}]})", {}));  // JSON Schema's integer
  CHECK(gltf_json_error(R"({"extensions": {"KHR_lights_punctual": {"lights": [{"intensity": "bright"}]}}})", {}) ==
        std::string("extensions.KHR_lights_punctual.lights[0].intensity: the string \"bright\" is not a number"));
  CHECK(gltf_json_error(R"({"extensionsRequired": ["KHR_materials_ior"]})", {"KHR_materials_ior"}) == std::nullopt);
  CHECK(gltf_json_error(R"({"extensionsRequired": ["EXT_x"]})", {}) == std::string("extensionsRequired: EXT_x is not an extension dstrans reads"));
  CHECK(gltf_json_error("[1, 2]", {}) == std::string("the file: an object is needed"));
  CHECK_FALSE(gltf_json_error("{not json", {}));  // the parser's to report
}

TEST_CASE("a scene written as glTF reads back as itself", "[scene][gltf]") {
  auto room = load_scene(std::string(DSTRANS_SOURCE_DIR) + "/examples/scenes/pane.json");
  REQUIRE(room);
  scene s = *room;
  s.particles.clear();  // glTF has no particle systems
  gltf_doc d = from_scene(s);
  auto back = load(d, "pane");
  INFO((back ? "" : back.error()));
  REQUIRE(back);
  REQUIRE(back->objects.size() == s.objects.size());
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    const object &a = s.objects[i], &b = back->objects[i];
    CHECK(b.geometry.positions == a.geometry.positions);
    REQUIRE(b.geometry.normals.size() == a.geometry.normals.size());
    for (std::size_t v = 0; v < a.geometry.normals.size(); ++v)  // made unit length again, within a rounding
      CHECK(glm::distance(b.geometry.normals[v], a.geometry.normals[v]) < 1e-6f);
    CHECK(b.geometry.indices == a.geometry.indices);
    CHECK(b.transform == a.transform);
    const material &ma = s.materials[a.material], &mb = back->materials[b.material];
    CHECK(mb.diffuse == ma.diffuse);
    CHECK(mb.alpha == Approx(ma.alpha));
    CHECK(mb.refractive == ma.refractive);
  }
  REQUIRE(back->lights.size() == s.lights.size());
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    const light &a = s.lights[i], &b = back->lights[i];
    CHECK(b.kind == a.kind);
    CHECK(b.colour == a.colour);
    CHECK(b.intensity == Approx(a.intensity));
    CHECK(glm::distance(b.direction, glm::normalize(a.direction)) < 1e-5f);
    if (a.kind == light_kind::directional) continue;
    CHECK(glm::distance(b.position, a.position) < 1e-4f);
    CHECK(b.range == Approx(a.range));
    if (a.kind != light_kind::spot) continue;
    CHECK(b.inner_angle == Approx(a.inner_angle));
    CHECK(b.outer_angle == Approx(a.outer_angle));
  }
  CHECK(glm::distance(back->view.position, s.view.position) < 1e-4f);
  CHECK(glm::dot(glm::normalize(back->view.target - back->view.position), glm::normalize(s.view.target - s.view.position)) ==
        Approx(1.0f));
  CHECK(back->view.fov_y == Approx(s.view.fov_y));
}

TEST_CASE("a scene file places glTF assets among its shapes", "[scene][gltf]") {
  gltf_doc d;
  d.j["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {0.25, 0.5, 0.75, 1.0}}}}}};
  d.mesh({{"attributes", {{"POSITION", d.positions(triangle)}}}, {"material", 0}}, {{"translation", {0, 0, 1}}});
  const std::string path = d.write("asset");
  const std::string folder = std::filesystem::path(path).parent_path().string();
  const std::string file = std::filesystem::path(path).filename().string();
  auto scene_with = [&](const std::string& object) {
    return R"({"camera": {"position": [0, 1, 5], "target": [0, 1, 0]},
               "materials": {"wall": {"diffuse": [0.8, 0.8, 0.8]}},
               "objects": [{"shape": "box", "size": [1, 1, 1], "material": "wall"}, )" +
           object + "]}";
  };
  // Relative to the scene file's folder: moved by (1, 2, 3), turned 90 degrees about y, scaled by 2.
  auto s = parse_scene(scene_with(R"({"gltf": ")" + file + R"(", "position": [1, 2, 3], "rotation_y": 90, "scale": 2})"),
                       folder + "/scene.json");
  INFO((s ? "" : s.error()));
  REQUIRE(s);
  REQUIRE(s->objects.size() == 2);
  REQUIRE(s->materials.size() == 2);
  CHECK(s->objects[1].material == 1);
  CHECK(s->materials[1].diffuse == glm::vec3(0.25f, 0.5f, 0.75f));
  CHECK(s->lights.empty());  // the asset's default light is not the scene's
  // The triangle's (1, 0, 0) at z = 1 in the asset: scaled (2, 0, 2), turned (2, 0, -2), moved (3, 2, 1).
  const glm::vec3 p = glm::vec3(s->objects[1].transform * glm::vec4(s->objects[1].geometry.positions[1], 1.0f));
  CHECK(glm::distance(p, glm::vec3(3, 2, 1)) < 1e-5f);
  // A missing asset, a broken one and one over the budget name the object.
  auto missing = parse_scene(scene_with(R"({"gltf": "no_such.glb"})"), folder + "/scene.json");
  REQUIRE_FALSE(missing);
  CHECK_THAT(missing.error(), Catch::StartsWith(folder + "/scene.json: objects[1].gltf: " + folder + "/no_such.glb: cannot read"));
  auto broken = parse_scene(scene_with(R"({"gltf": ")" + models + R"(/wrongTypes/badArray.gltf"})"), folder + "/scene.json");
  REQUIRE_FALSE(broken);
  CHECK_THAT(broken.error(), Catch::EndsWith("objects[1].gltf: " + models + "/wrongTypes/badArray.gltf: meshes[0].primitives: an array is needed"));
  auto unknown = parse_scene(scene_with(R"({"gltf": ")" + file + R"(", "material": "wall"})"), folder + "/scene.json");
  REQUIRE_FALSE(unknown);
  CHECK_THAT(unknown.error(), Catch::Contains("objects[1]"));
  auto far = parse_scene(scene_with(R"({"gltf": ")" + file + R"(", "scale": 1e6, "position": [1e6, 0, 0]})"), folder + "/scene.json");
  REQUIRE(far);  // large, and still within the float range
  gltf_doc huge;
  huge.mesh({{"attributes", {{"POSITION", huge.positions({0, 0, 0, 3e33f, 0, 0, 0, 1, 0})}}}});
  const std::string huge_path = huge.write("huge");
  auto past = parse_scene(scene_with(R"({"gltf": ")" + std::filesystem::path(huge_path).filename().string() + R"(", "scale": 1e6})"),
                          folder + "/scene.json");
  std::filesystem::remove(huge_path);
  REQUIRE_FALSE(past);
  CHECK_THAT(past.error(), Catch::EndsWith("objects[1].scale: places the asset past the float range"));
  scene_budget tight;
  tight.bytes = 26 * bytes_per_vertex;  // the box's 24 vertices fit, the triangle's 3 more do not
  auto over = parse_scene(scene_with(R"({"gltf": ")" + file + R"("})"), folder + "/scene.json", tight);
  std::filesystem::remove(path);
  REQUIRE_FALSE(over);
  CHECK_THAT(over.error(), Catch::Contains("objects[1].gltf") && Catch::Contains("over the budget"));
}

// As scene_fuzz_test.cpp for scene files: glass_shelf.gltf and assimp's embedded box mutated as JSON, and
// the binary box with bytes changed or cut, each loaded from a file. Every case is a scene with finite
// positions and unit normals or a short error naming the file, never a crash (the sanitizer build runs it).
TEST_CASE("900 mutated glTF files each load or give a short error", "[scene][gltf][fuzz]") {
  auto read = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string shelf = read(std::string(DSTRANS_SOURCE_DIR) + "/examples/scenes/glass_shelf.gltf"),
                    box = read(models + "/BoxTextured-glTF-Embedded/BoxTextured.gltf"),
                    glb = read(models + "/BoxTextured-glTF-Binary/BoxTextured.glb");
  REQUIRE(glb_json(glb));
  const std::string base = (std::filesystem::temp_directory_path() / ("dstrans_" + std::to_string(getpid()) + "_fuzz")).string();
  std::mt19937 rng(20261203u);
  scene_budget budget;
  budget.bytes = std::size_t(256) << 20;
  std::size_t loaded = 0, refused = 0;
  for (int i = 0; i < 900; ++i) {
    std::string data, path = base + ".gltf";
    if (i % 3 == 2) {
      data = glb;
      path = base + ".glb";
      if (rng() % 4 == 0) data.resize(rng() % (data.size() + 1));
      else
        for (int k = 0; k < 1 + int(rng() % 8); ++k) data[rng() % data.size()] = char(rng() % 256);
    } else {
      data = mutate(i % 3 ? box : shelf, rng);
    }
    std::ofstream(path, std::ios::binary) << data;
    const auto s = load_gltf(path, budget);
    INFO("case " << i);
    if (s) {
      ++loaded;
      const scene_mesh m = flatten(*s);
      for (const glm::vec3& p : m.positions) CHECK(std::isfinite(p.x + p.y + p.z));
      for (const glm::vec3& n : m.normals) CHECK(glm::length(n) == Approx(1.0f).margin(1e-3));
      for (std::uint32_t k : m.indices) CHECK(k < m.positions.size());
    } else {
      ++refused;
      INFO(s.error().substr(0, 200));
      CHECK(s.error().rfind(path + ": ", 0) == 0);
      CHECK(s.error().size() < 500);
    }
  }
  std::filesystem::remove(base + ".gltf");
  std::filesystem::remove(base + ".glb");
  CHECK(loaded > 50);
  CHECK(refused > 300);
}

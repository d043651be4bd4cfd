// Procedural shapes, scene flattening, and scene files: good ones load, bad ones name the field.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include <dstrans/closed_surface.hpp>
#include <dstrans/particles.hpp>
#include <dstrans/scene.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <json_input.hpp>
#include <same_objects.hpp>
#include <scene_json.hpp>

using namespace dstrans;

namespace {
// Each triangle's winding agrees with its vertices' normals (counter-clockwise seen from outside).
bool wound_with_normals(const shape& s) {
  for (std::size_t i = 0; i < s.indices.size(); i += 3) {
    const glm::vec3 a = s.positions[s.indices[i]], b = s.positions[s.indices[i + 1]], c = s.positions[s.indices[i + 2]];
    const glm::vec3 face = glm::cross(b - a, c - a);
    if (glm::length(face) < 1e-9f) continue;  // degenerate seam triangles carry no winding
    const glm::vec3 n = s.normals[s.indices[i]] + s.normals[s.indices[i + 1]] + s.normals[s.indices[i + 2]];
    if (glm::dot(face, n) <= 0.0f) return false;
  }
  return true;
}

const char* const good =
    R"({"camera": {"position": [0, 1, 5], "target": [0, 1, 0], "fov_y": 50},
        "ambient": [0.1, 0.1, 0.1],
        "materials": {"wall": {"diffuse": [0.8, 0.8, 0.8]},
                      "glass": {"diffuse": [0.2, 0.5, 1.0], "alpha": 0.4, "spec_intensity": 0.9, "spec_power": 64, "refractive": true}},
        "objects": [{"shape": "room", "size": [10, 4, 10], "material": "wall"},
                    {"shape": "pane", "size": [2, 1.5], "position": [0, 1, 0], "rotation_y": 15, "material": "glass"},
                    {"shape": "bottle", "radius": 0.2, "height": 0.8, "segments": 24, "material": "glass"}],
        "lights": [{"type": "spot", "position": [0, 3, 2], "direction": [0, -1, -0.5], "colour": [1, 0.9, 0.8],
                    "intensity": 2, "range": 8, "inner_angle": 20, "outer_angle": 30, "shadows": true},
                   {"type": "point", "position": [1, 2, 1], "range": 5},
                   {"type": "directional", "direction": [0.3, -1, 0.2], "intensity": 0.3}],
        "particles": [{"material": "wall", "base": [1, 0, 0], "radius": 0.3, "height": 1.5, "size": 0.2, "count": 50, "seed": 4}],
        "post": [{"effect": "aa", "interlace": false}, {"effect": "bloom", "threshold": 0.9, "radius": 3}, {"effect": "sepia"}]})";

// The scene `good` with `from` replaced by `to`.
std::string edit(const std::string& from, const std::string& to) {
  std::string s = good;
  const std::size_t at = s.find(from);
  REQUIRE(at != std::string::npos);
  return s.replace(at, from.size(), to);
}
}  // namespace

TEST_CASE("shapes are wound with their normals and have the expected size", "[scene]") {
  const shape box = shape_box({1, 2, 3});
  CHECK(box.triangles() == 12);
  CHECK(wound_with_normals(box));
  const shape room = shape_room({10, 4, 10});
  CHECK(wound_with_normals(room));
  for (const glm::vec3& p : room.positions) CHECK((p.y == 0.0f || p.y == 4.0f));
  CHECK(room.normals[0] == glm::vec3(0, 0, -1));  // the back wall's inside faces the room
  CHECK(wound_with_normals(shape_pane({2, 1})));
  const shape sphere = shape_sphere(0.5f, 32);
  CHECK(sphere.triangles() == 2u * 32u * 16u);
  CHECK(wound_with_normals(sphere));
  for (const glm::vec3& p : sphere.positions) CHECK(glm::length(p) == Approx(0.5f).margin(1e-5));
  CHECK(wound_with_normals(shape_cylinder(0.3f, 1.0f, 16)));
  const shape bottle = shape_bottle(0.2f, 0.8f, 24);
  CHECK(wound_with_normals(bottle));
  float top = 0.0f;
  for (const glm::vec3& p : bottle.positions) top = std::max(top, p.y);
  CHECK(top == Approx(0.8f));
}

TEST_CASE("flatten puts every object in world space with its material", "[scene]") {
  scene s;
  s.materials = {material{}, material{}};
  s.objects.push_back({shape_pane({2, 2}), glm::translate(glm::mat4(1.0f), glm::vec3(5, 0, 0)), 1});
  s.objects.push_back({shape_box({1, 1, 1}), glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(0, 1, 0)), 0});
  const scene_mesh m = flatten(s);
  REQUIRE(m.positions.size() == 4 + 24);
  CHECK(m.positions[0] == glm::vec3(4, -1, 0));
  CHECK(m.materials[0] == 1);
  CHECK(m.materials[4] == 0);
  CHECK(m.indices.size() == 6 + 36);
  CHECK(m.indices[6] == 4);  // the box's indices follow the pane's vertices
  CHECK(m.normals[4].x == Approx(1.0f));  // the box's +Z face turned to +X
  // Each object is a part: its indices, in order, and a sphere that holds its vertices.
  REQUIRE(m.parts.size() == 2);
  CHECK(m.parts[0].first == 0);
  CHECK(m.parts[0].count == 6);
  CHECK(m.parts[1].first == 6);
  CHECK(m.parts[1].count == 36);
  CHECK(m.parts[0].centre == glm::vec3(5, 0, 0));
  CHECK(m.parts[0].radius == Approx(std::sqrt(2.0f)));
  CHECK(m.parts[1].radius == Approx(std::sqrt(0.75f)));
}

TEST_CASE("same_objects tells frames that can share their meshes; a moved, changed or added object differs", "[scene]") {
  scene still;
  still.materials = {material{}, material{glm::vec3(1.0f), 0.5f}};
  still.objects.push_back({shape_pane({2, 2}), glm::mat4(1.0f), 1});
  still.objects.push_back({shape_box({1, 1, 1}), glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -2)), 0});
  scene turned = still;  // another camera: the same objects
  turned.view.position = glm::vec3(3, 1, 4);
  CHECK(render::same_objects(still, turned));
  scene moved = still, changed = still, added = still, recoloured = still, nan = still;
  moved.objects[0].transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.02f, 0, 0));
  changed.objects[1].geometry.positions[3].y += 1e-6f;
  added.objects.push_back(still.objects[0]);
  recoloured.objects[1].material = 1;
  nan.objects[0].geometry.normals[0].x = std::numeric_limits<float>::quiet_NaN();
  for (const scene* other : {&moved, &changed, &added, &recoloured}) CHECK_FALSE(render::same_objects(still, *other));
  CHECK_FALSE(render::same_objects(nan, nan));
  // Each frame shares the meshes of the first frame with its objects.
  CHECK(render::first_with_same_objects({still, turned, moved, still, moved, added}) ==
        std::vector<std::size_t>{0, 0, 2, 0, 2, 5});
  CHECK(render::first_with_same_objects({nan, nan}) == std::vector<std::size_t>{0, 1});
  CHECK(render::first_with_same_objects({}).empty());
}

TEST_CASE("flatten's parts tile the indices, hair last, each sphere holding its object's vertices", "[scene]") {
  scene s;
  s.materials = {material{}, material{}};
  s.materials[1].hair = true;
  s.objects.push_back({shape_hair(0.5f, 20, 1.0f, 0.01f, 4, 7), glm::mat4(1.0f), 1});
  s.objects.push_back({shape_sphere(1.0f, 12), glm::translate(glm::mat4(1.0f), glm::vec3(0, 3, -2)), 0});
  s.objects.push_back({shape_box({0, 0, 0}), glm::mat4(1.0f), 0});  // one point: radius 0
  const scene_mesh m = flatten(s);
  REQUIRE(m.parts.size() == 3);
  std::size_t next = 0;
  for (const mesh_part& part : m.parts) {
    CHECK(part.first == next);
    next += part.count;
    for (std::size_t i = part.first; i < part.first + part.count; ++i)
      CHECK(glm::length(m.positions[m.indices[i]] - part.centre) <= part.radius * 1.0001f + 1e-6f);
  }
  CHECK(next == m.indices.size());
  CHECK(m.parts[2].first == m.hair_first);  // the hair, listed first, is drawn last
  CHECK(m.parts[1].radius == 0.0f);
}

TEST_CASE("a material is opaque unless transparent, alpha-tested or hair, and flatten's parts say which are", "[scene]") {
  scene s;
  s.materials.resize(5);
  s.materials[1].alpha = 0.5f;         // glass
  s.materials[2].alpha_cutoff = 0.5f;  // alpha-tested: some fragments dropped
  s.materials[3].hair = true;
  s.materials[4].texture = 0;          // a texture does not lower an opaque material's alpha
  s.materials[4].alpha = std::numeric_limits<float>::quiet_NaN();  // NaN alpha is opaque, as dst_transparent has it
  const bool want[] = {true, false, false, false, true};
  for (std::size_t i = 0; i < s.materials.size(); ++i) {
    INFO("material " << i);
    CHECK(s.materials[i].opaque() == want[i]);
    s.objects.push_back({shape_box({1, 1, 1}), glm::mat4(1.0f), std::uint32_t(i)});
  }
  s.objects.push_back({shape_box({1, 1, 1}), glm::mat4(1.0f), 9});  // no such material
  const scene_mesh m = flatten(s);
  REQUIRE(m.parts.size() == 6);
  // In index order: materials 0, 1, 2, 4, the missing one, then the hair (3).
  const bool parts_want[] = {true, false, false, true, false, false};
  for (std::size_t i = 0; i < m.parts.size(); ++i) {
    INFO("part " << i);
    CHECK(m.parts[i].opaque == parts_want[i]);
  }
}

TEST_CASE("closed_orientation: which way a closed mesh faces, by its points, and 0 for anything open", "[scene][culling]") {
  CHECK(closed_orientation(shape_box({1, 2, 3}).positions, shape_box({1, 2, 3}).indices) == 1);
  const shape room = shape_room({12, 4, 12});
  CHECK(closed_orientation(room.positions, room.indices) == -1);  // turned inwards
  // Revolved shapes: seams of repeated vertices, and triangles with two corners at a pole or on a rim
  // (a cylinder repeats its rims' rings for sharp normals), which cover nothing.
  for (int slices : {3, 4, 40}) {
    INFO(slices << " slices");
    for (const shape& c : {shape_sphere(0.16f, slices), shape_cylinder(0.09f, 0.35f, slices), shape_bottle(0.1f, 0.45f, slices)})
      CHECK(closed_orientation(c.positions, c.indices) == 1);
  }
  const shape pane = shape_pane({2, 1});
  CHECK(closed_orientation(pane.positions, pane.indices) == 0);
  // The pane and its back, turned round: closed, but flat.
  shape sheet = pane;
  for (std::size_t i = 0; i < pane.indices.size(); i += 3)
    sheet.indices.insert(sheet.indices.end(), {pane.indices[i], pane.indices[i + 2], pane.indices[i + 1]});
  CHECK(closed_orientation(sheet.positions, sheet.indices) == 0);
  shape box = shape_box({1, 1, 1});
  shape open = box;
  open.indices.resize(open.indices.size() - 3);  // a hole
  CHECK(closed_orientation(open.positions, open.indices) == 0);
  shape flipped = box;
  std::swap(flipped.indices[1], flipped.indices[2]);  // one triangle turned round
  CHECK(closed_orientation(flipped.positions, flipped.indices) == 0);
  // Two pieces: both outwards, or one of them inside out.
  shape two = box, mixed = box;
  for (shape* t : {&two, &mixed}) {
    const auto base = std::uint32_t(t->positions.size());
    for (glm::vec3 p : box.positions) t->positions.push_back(p + glm::vec3(3, 0, 0));
    for (std::size_t i = 0; i < box.indices.size(); i += 3)
      t->indices.insert(t->indices.end(), {base + box.indices[i], base + box.indices[i + (t == &two ? 1 : 2)],
                                           base + box.indices[i + (t == &two ? 2 : 1)]});
  }
  CHECK(closed_orientation(two.positions, two.indices) == 1);
  CHECK(closed_orientation(mixed.positions, mixed.indices) == 0);
  CHECK(closed_orientation({}, {}) == 0);
  shape out_of_range = box;
  out_of_range.indices.back() = 999;
  CHECK(closed_orientation(out_of_range.positions, out_of_range.indices) == 0);
  shape nan = box;
  nan.positions[0].x = std::numeric_limits<float>::quiet_NaN();
  CHECK(closed_orientation(nan.positions, nan.indices) == 0);
  // -0 is the point +0 is.
  std::vector<glm::vec3> tetra = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-0.0f, 0, 0}};
  CHECK(closed_orientation(tetra, {0, 2, 1, 4, 1, 3, 0, 3, 2, 1, 2, 3}) == 1);
}

TEST_CASE("flatten's parts are closed where their triangles face out of a closed surface in world space and drop no fragment",
          "[scene][culling]") {
  scene s;
  s.materials.resize(4);
  s.materials[1].alpha = 0.5f;         // glass: its nearest surface is kept as an opaque one's
  s.materials[2].alpha_cutoff = 0.5f;  // alpha-tested: a back face shows through the holes
  s.materials[3].hair = true;
  const glm::mat4 mirror = glm::scale(glm::mat4(1.0f), glm::vec3(-1, 1, 1));
  s.objects = {{shape_box({1, 1, 1}), glm::mat4(1.0f), 0}, {shape_sphere(1.0f, 12), glm::mat4(1.0f), 1},
               {shape_box({1, 1, 1}), glm::mat4(1.0f), 2}, {shape_pane({1, 1}), glm::mat4(1.0f), 0},
               {shape_box({1, 1, 1}), mirror, 0},  // a mirror turns its faces inwards
               {shape_room({4, 4, 4}), glm::mat4(1.0f), 0}, {shape_room({4, 4, 4}), mirror, 0},  // and a room's outwards
               {shape_box({1, 1, 1}), glm::mat4(1.0f), 3}};
  const scene_mesh m = flatten(s);
  REQUIRE(m.parts.size() == 8);
  const bool want[] = {true, true, false, false, false, false, true, false};
  for (std::size_t i = 0; i < m.parts.size(); ++i) {
    INFO("part " << i);
    CHECK(m.parts[i].closed == want[i]);
  }
}

TEST_CASE("a good scene file loads", "[scene]") {
  const auto s = parse_scene(good, "good.json");
  REQUIRE(s);
  CHECK(s->materials.size() == 2);
  CHECK(s->objects.size() == 3);
  CHECK(s->objects[1].material == 0);  // "glass" sorts before "wall"
  CHECK(s->materials[0].transparent());
  CHECK(s->materials[0].refractive);
  REQUIRE(s->lights.size() == 3);
  CHECK(s->lights[0].kind == light_kind::spot);
  CHECK(s->lights[0].shadows);
  CHECK(glm::length(s->lights[0].direction) == Approx(1.0f));
  CHECK(s->lights[1].kind == light_kind::point);
  CHECK_FALSE(s->lights[2].shadows);
  const auto sun = parse_scene(edit("\"intensity\": 0.3}", "\"intensity\": 0.3, \"shadows\": true}"), "sun.json");
  REQUIRE(sun);
  CHECK(sun->lights[2].shadows);
  CHECK(s->view.fov_y == 50.0f);
  CHECK(s->ambient == glm::vec3(0.1f));
  REQUIRE(s->particles.size() == 1);
  CHECK(s->particles[0].material == 1);
  CHECK(s->particles[0].base == glm::vec3(1, 0, 0));
  CHECK(s->particles[0].count == 50);
  CHECK(s->particles[0].seed == 4u);
  REQUIRE(s->post.size() == 3);
  CHECK(s->post[0].kind == post_kind::antialias);
  CHECK_FALSE(s->post[0].interlace);
  CHECK(s->post[1].threshold == 0.9f);
  CHECK(s->post[1].radius == 3);
  CHECK(s->post[2].kind == post_kind::sepia);
  const auto chain = parse_post_chain(R"({"post": [{"effect": "dof", "focus": 3, "range": 1}]})", "chain.json");
  REQUIRE(chain);
  REQUIRE(chain->size() == 1);
  CHECK((*chain)[0].focus == 3.0f);
}

TEST_CASE("bad scene files get an error that names the field", "[scene]") {
  const std::map<std::string, std::string> cases{
      {edit("\"fov_y\": 50", "\"fov_y\": \"wide\""), "good.json: camera.fov_y: expected a number, got the string \"wide\""},
      {edit("\"target\": [0, 1, 0], ", ""), "good.json: camera.target: missing"},
      {edit("\"size\": [2, 1.5]", "\"size\": [2, -1.5]"), "good.json: objects[1].size[1]: -1.5 is outside"},
      {edit("\"size\": [2, 1.5]", "\"size\": [2, 1.5, 3]"), "good.json: objects[1].size: expected an array of 2 numbers"},
      {edit("\"radius\": 0.2", "\"radius\": 1e999"), "good.json: not valid JSON: [json.exception.out_of_range.406] number overflow parsing '1e999'"},
      {edit("\"rotation_y\": 15", "\"rotaton_y\": 15"), "good.json: objects[1].rotaton_y: unknown key"},
      {edit("\"material\": \"wall\"", "\"material\": \"brick\""), "good.json: objects[0].material: unknown material 'brick'"},
      {edit("\"shape\": \"room\"", "\"shape\": \"torus\""), "good.json: objects[0].shape: unknown shape 'torus'"},
      {edit("\"outer_angle\": 30", "\"outer_angle\": 120"), "good.json: lights[0].outer_angle: 120"},
      {edit("\"type\": \"point\"", "\"type\": \"area\""), "good.json: lights[1].type: unknown light type 'area'"},
      {edit("\"alpha\": 0.4", "\"alpha\": NaN"), "good.json: not valid JSON"},
      {edit("\"shadows\": true", "\"shadows\": 1"), "good.json: lights[0].shadows: expected true or false"},
      {edit("\"direction\": [0.3, -1, 0.2]", "\"direction\": [0, 0, 0]"), "good.json: lights[2].direction: must not be zero"},
      {R"({"camera": {"position": [0, 1, 5], "target": [0, 1, 0]}, "materials": {"a": {}}, "objects": []})",
       "good.json: objects: expected an array with at least one object"},
      {"[]", "good.json: expected an object"},
      {edit("\"effect\": \"sepia\"", "\"effect\": \"vignette\""), "good.json: post[2].effect: unknown effect 'vignette'"},
      {edit("\"threshold\": 0.9", "\"focus\": 0.9"), "good.json: post[1].focus: unknown key"},
      {edit("\"radius\": 3}", "\"radius\": 65}"), "good.json: post[1].radius: 65 is outside"},
      {edit("\"material\": \"wall\", \"base\"", "\"material\": \"smoke\", \"base\""), "good.json: particles[0].material: unknown material 'smoke'"},
      {edit("\"count\": 50", "\"count\": -1"), "good.json: particles[0].count: -1 is outside"},
      {edit("\"seed\": 4", "\"seeds\": 4"), "good.json: particles[0].seeds: unknown key"},
  };
  for (const auto& [text, message] : cases) {
    const auto s = parse_scene(text, "good.json");
    INFO(message);
    REQUIRE_FALSE(s);
    CHECK_THAT(s.error(), Catch::StartsWith(message));
  }
  const auto missing = load_scene("no/such/scene.json");
  REQUIRE_FALSE(missing);
  CHECK(missing.error() == "no/such/scene.json: cannot read the scene file: No such file or directory");
}

TEST_CASE("glass_room and its variants: the thesis's scene at equal triangle counts", "[scene]") {
  std::size_t counts[3] = {};
  double shares[3] = {};
  int k = 0;
  for (const char* file : {"glass_room.json", "glass_room_17.json", "glass_room_0.json"}) {
    const auto s = load_scene(std::string(DSTRANS_SOURCE_DIR) + "/examples/scenes/" + file);
    INFO(s.error());
    REQUIRE(s);
    std::size_t total = 0, clear = 0, shadowed_spots = 0;
    for (const object& o : s->objects) {
      total += o.geometry.triangles();
      if (s->materials[o.material].transparent()) clear += o.geometry.triangles();
    }
    for (const light& l : s->lights) shadowed_spots += l.kind == light_kind::spot && l.shadows;
    CHECK(shadowed_spots == 64);
    CHECK(s->lights.size() == 67);
    counts[k] = total;
    shares[k++] = double(clear) / double(total);
  }
  CHECK(counts[0] > 55000);
  CHECK(counts[0] < 65000);
  CHECK(counts[1] == counts[0]);
  CHECK(counts[2] == counts[0]);
  CHECK(shares[0] == Approx(0.35).margin(0.04));  // about a third
  CHECK(shares[1] == Approx(0.17).margin(0.005));
  CHECK(shares[2] == 0.0);
}

TEST_CASE("particle systems: the same particles for a seed, centred inside their bounds, drawn back to front facing the camera",
          "[scene][particles]") {
  particle_system ps;
  ps.base = {1.0f, 0.5f, -2.0f};
  ps.radius = 0.6f;
  ps.height = 2.0f;
  ps.size = 0.3f;
  ps.count = 200;
  const std::vector<particle> a = emit(ps), again = emit(ps);
  REQUIRE(a.size() == 200u);
  ps.seed = 2;
  const std::vector<particle> other = emit(ps);
  bool differs = false;
  const auto [lo, hi] = particle_bounds(ps);
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK(a[i].position == again[i].position);
    differs = differs || a[i].position != other[i].position;
    CHECK(a[i].size <= ps.size);
    CHECK(a[i].alpha > 0.0f);
    CHECK(a[i].alpha <= 1.0f);
    // Every centre is in the box the light volume spans.
    CHECK(glm::all(glm::lessThanEqual(lo, a[i].position)));
    CHECK(glm::all(glm::lessThanEqual(a[i].position, hi)));
  }
  CHECK(differs);

  scene s;
  s.materials = {material{}};
  s.particles = {ps, ps};
  s.particles[1].base = {-1.0f, 0.0f, 1.0f};
  s.view.position = {0.0f, 2.0f, 6.0f};
  const std::vector<particle_vertex> quads = particle_quads(s, s.view);
  REQUIRE(quads.size() == 2u * 200u * 6u);
  const glm::mat4 view = s.view.view();
  float last = -INFINITY;
  std::size_t systems[2] = {};
  for (std::size_t q = 0; q < quads.size(); q += 6) {
    // The quad's centre, its distance along the view direction (farther first), its plane facing the camera.
    const glm::vec3 centre = (quads[q].position + quads[q + 2].position) * 0.5f;
    const float depth = (view * glm::vec4(centre, 1.0f)).z;
    CHECK(depth >= last - 1e-4f);
    last = depth;
    const glm::vec3 across = glm::vec3(view * glm::vec4(quads[q + 2].position - quads[q].position, 0.0f));
    CHECK(std::abs(across.z) < 1e-4f);
    CHECK(quads[q].corner == glm::vec2(-1.0f, -1.0f));
    CHECK(quads[q + 2].corner == glm::vec2(1.0f, 1.0f));
    // Every corner leads back to the centre by its corner and size, as the particle pass finds the cell it reads.
    const glm::vec3 right(view[0][0], view[1][0], view[2][0]), up(view[0][1], view[1][1], view[2][1]);
    for (std::size_t k = q; k < q + 6; ++k) {
      const particle_vertex& v = quads[k];
      CHECK(v.size == quads[q].size);
      CHECK(v.size > 0.0f);
      CHECK(v.size <= ps.size);
      CHECK(glm::length(v.position - v.size * (v.corner.x * right + v.corner.y * up) - centre) < 1e-4f);
    }
    ++systems[quads[q].system];
  }
  CHECK(systems[0] == 200u);
  CHECK(systems[1] == 200u);
}

TEST_CASE("hostile scene files get a short error, not a crash, a silent rounding or all the memory", "[scene][hostile]") {
  // 100,000 nested arrays where a number goes: refused while parsing, before anything recurses over it.
  const std::string deep = edit("\"fov_y\": 50", "\"fov_y\": " + std::string(100000, '[') + std::string(100000, ']'));
  const auto nested = parse_scene(deep, "good.json");
  REQUIRE_FALSE(nested);
  CHECK_THAT(nested.error(), Catch::Contains("nested more than 32 levels deep"));
  // A value quoted in an error is an excerpt: a million-number ambient gives a line, not megabytes.
  std::string many = "[0";
  for (int i = 0; i < 1000000; ++i) many += ",0";
  const auto huge = parse_scene(edit("\"ambient\": [0.1, 0.1, 0.1]", "\"ambient\": " + many + "]"), "good.json");
  REQUIRE_FALSE(huge);
  CHECK(huge.error() == "good.json: ambient: expected an array of 3 numbers, got an array of 1000001 values");
  // Whole numbers stay whole.
  for (const auto& [from, to, field] : {std::tuple{"\"segments\": 24", "\"segments\": 3.7", "objects[2].segments"},
                                        std::tuple{"\"count\": 50", "\"count\": 0.5", "particles[0].count"},
                                        std::tuple{"\"seed\": 4", "\"seed\": 18446744073709551615", "particles[0].seed"}}) {
    const auto s = parse_scene(edit(from, to), "good.json");
    INFO(to);
    REQUIRE_FALSE(s);
    CHECK_THAT(s.error(), Catch::StartsWith(std::string("good.json: ") + field + ": "));
  }
  CHECK_THAT(parse_scene(edit("\"segments\": 24", "\"segments\": 3.7"), "good.json").error(), Catch::Contains("expected a whole number, got 3.7"));
  // The budget: estimated before building, refused with the estimate.
  const auto hair = parse_scene(edit("{\"shape\": \"bottle\"", "{\"shape\": \"hair\", \"radius\": 0.5, \"strands\": 100000, \"length\": 1, \"segments\": 8, \"material\": \"wall\"}, {\"shape\": \"bottle\""), "good.json");
  REQUIRE_FALSE(hair);
  CHECK_THAT(hair.error(), Catch::Matches("good.json: objects\\[2\\]\\.shape: the scene would take about [0-9]+ MiB by here \\(6400[0-9]+ vertices, 0 particles, 0 lights\\), over the budget of 1024 MiB \\(--budget MIB raises it\\)"));
  std::string systems;
  for (int i = 0; i < 40; ++i) systems += std::string(i ? ", " : "") + "{\"material\": \"wall\", \"base\": [0, 0, 0], \"count\": 1000000}";
  const auto smoke = parse_scene(edit("\"particles\": [", "\"particles\": [" + systems + ", "), "good.json");
  REQUIRE_FALSE(smoke);
  CHECK_THAT(smoke.error(), Catch::Contains("particles[1].count: the scene would take about"));
  scene_budget roomy;
  roomy.bytes = std::size_t(8) << 30;
  CHECK(parse_scene(edit("\"count\": 50", "\"count\": 1000000"), "good.json", roomy));
}

TEST_CASE("a scene path that is no plain file, or too large a file, is refused unread", "[scene][hostile]") {
  const auto zero = load_scene("/dev/zero");
  REQUIRE_FALSE(zero);
  CHECK(zero.error() == "/dev/zero: not a plain file, so not read as a scene file");
  const auto folder = load_scene(DSTRANS_SOURCE_DIR);
  REQUIRE_FALSE(folder);
  CHECK(folder.error() == std::string(DSTRANS_SOURCE_DIR) + ": a folder, not a scene file");
  scene_budget small;
  small.file_bytes = 100;
  const auto big = load_scene(std::string(DSTRANS_SOURCE_DIR) + "/examples/scenes/pane.json", small);
  REQUIRE_FALSE(big);
  CHECK_THAT(big.error(), Catch::EndsWith("bytes, more than a scene file may have (100)"));
}

TEST_CASE("a camera looking straight up or down gets a well-defined view", "[scene]") {
  for (float y : {3.0f, -3.0f}) {
    camera c;
    c.position = {0.0f, y, 0.0f};
    c.target = {0.0f, 0.0f, 0.0f};
    const glm::mat4 v = c.view();
    INFO("camera at y = " << y);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) CHECK(std::isfinite(v[i][j]));
    // The image's top points along -Z looking down, +Z looking up; the view axis is the camera's.
    const glm::vec3 up = glm::vec3(glm::inverse(v) * glm::vec4(0, 1, 0, 0));
    CHECK(up.z == Approx(y > 0.0f ? -1.0f : 1.0f));
    const glm::vec3 forward = glm::vec3(glm::inverse(v) * glm::vec4(0, 0, -1, 0));
    CHECK(forward.y == Approx(y > 0.0f ? -1.0f : 1.0f));
  }
  camera tilted;
  tilted.position = {0.0f, 3.0f, 0.5f};
  tilted.target = {0.0f, 0.0f, 0.0f};
  CHECK(tilted.up() == glm::vec3(0.0f, 1.0f, 0.0f));  // anything off the vertical keeps +Y
}

TEST_CASE("budget messages give MiB rounded up", "[scene]") {
  CHECK(mib(0) == "0");
  CHECK(mib(1) == "1");
  CHECK(mib(std::size_t(1) << 20) == "1");
  CHECK(mib((std::size_t(1) << 20) + 1) == "2");
}

TEST_CASE("user JSON is parsed with its depth and size bounded, and quoted by excerpts", "[scene][hostile]") {
  using json = nlohmann::json;
  CHECK(parse_bounded<json>("[1, [2, [3]]]") == json::parse("[1, [2, [3]]]"));
  CHECK_THROWS_AS(parse_bounded<json>(std::string(40, '[') + std::string(40, ']')), json_too_big);
  // The bound counts the parser's events: the array's start and end and its three numbers are five.
  CHECK_THROWS_AS(parse_bounded<json>("[1, 2, 3]", 4), json_too_big);
  CHECK(parse_bounded<json>("[1, 2, 3]", 5).size() == 3);
  CHECK(key_excerpt("short") == "short");
  CHECK(key_excerpt(std::string(100, 'k')) == std::string(40, 'k') + "...");
  CHECK(excerpt(json::parse("[1, 2]")) == "an array of 2 values");
  CHECK(excerpt(json("abc")) == "the string \"abc\"");
}

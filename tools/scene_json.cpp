// Implements scene_json.hpp with nlohmann-json.
#include "scene_json.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <dstrans/material_textures.hpp>
#include <nlohmann/json.hpp>

#include <sys/stat.h>

#include "json_input.hpp"
#include "scene_gltf.hpp"

namespace dstrans {

namespace {

using json = nlohmann::json;

struct bad_field {
  std::string message;
};

std::string show(float v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", double(v));
  return text;
}

// A JSON object being read: every key read is remembered, so that the rest can be reported as unknown.
class reader {
 public:
  reader(const json& j, std::string path) : j_(j), path_(std::move(path)) {
    if (!j_.is_object()) throw bad_field{where() + "expected an object"};
  }

  bool has(const std::string& key) {
    read_.insert(key);
    return j_.contains(key);
  }

  float number(const std::string& key, float fallback, float lo, float hi) {
    if (!has(key)) return fallback;
    return number_at(j_[key], field(key), lo, hi);
  }
  float number(const std::string& key, float lo, float hi) {
    require(key);
    return number(key, 0.0f, lo, hi);
  }
  template <int N>
  glm::vec<N, float> vec(const std::string& key, glm::vec<N, float> fallback, float lo, float hi) {
    if (!has(key)) return fallback;
    const json& v = j_[key];
    if (!v.is_array() || v.size() != N)
      throw bad_field{field(key) + ": expected an array of " + std::to_string(N) + " numbers, got " + excerpt(v)};
    glm::vec<N, float> out;
    for (int i = 0; i < N; ++i) out[i] = number_at(v[std::size_t(i)], field(key) + "[" + std::to_string(i) + "]", lo, hi);
    return out;
  }
  template <int N>
  glm::vec<N, float> vec(const std::string& key, float lo, float hi) {
    require(key);
    return vec<N>(key, glm::vec<N, float>(0.0f), lo, hi);
  }
  // A whole number in [lo, hi]: 3.7 segments or 0.5 particles are mistakes, not 3 and 0.
  std::int64_t integer(const std::string& key, std::int64_t fallback, std::int64_t lo, std::int64_t hi) {
    if (!has(key)) return fallback;
    const json& v = j_[key];
    const std::string name = field(key);
    const double d = v.is_number() ? v.get<double>() : NAN;
    if (!std::isfinite(d) || d != std::floor(d)) throw bad_field{name + ": expected a whole number, got " + excerpt(v)};
    if (d < double(lo) || d > double(hi))
      throw bad_field{name + ": " + excerpt(v) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]"};
    return std::int64_t(d);
  }
  std::int64_t integer(const std::string& key, std::int64_t lo, std::int64_t hi) {
    require(key);
    return integer(key, 0, lo, hi);
  }
  bool boolean(const std::string& key, bool fallback) {
    if (!has(key)) return fallback;
    if (!j_[key].is_boolean()) throw bad_field{field(key) + ": expected true or false, got " + excerpt(j_[key])};
    return j_[key].get<bool>();
  }
  std::string text(const std::string& key) {
    require(key);
    if (!j_[key].is_string()) throw bad_field{field(key) + ": expected a string, got " + excerpt(j_[key])};
    return j_[key].get<std::string>();
  }
  const json& raw(const std::string& key) {
    require(key);
    return j_[key];
  }
  std::string field(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  // Call when done: any key that was never read is a mistake in the file.
  void finish() const {
    for (const auto& [key, value] : j_.items())
      if (!read_.count(key)) throw bad_field{field(key) + ": unknown key"};
  }

 private:
  std::string where() const { return path_.empty() ? "" : path_ + ": "; }
  void require(const std::string& key) {
    if (!has(key)) throw bad_field{field(key) + ": missing"};
  }
  static float number_at(const json& v, const std::string& name, float lo, float hi) {
    if (!v.is_number()) throw bad_field{name + ": expected a number, got " + excerpt(v)};
    const double d = v.get<double>();
    if (!std::isfinite(d)) throw bad_field{name + ": must be finite"};
    if (d < lo || d > hi)
      throw bad_field{name + ": " + excerpt(v) + " is outside [" + show(lo) + ", " + show(hi) + "]"};
    return float(d);
  }

  const json& j_;
  std::string path_;
  std::set<std::string> read_;
};

constexpr float big = 1e6f;

// The scene's estimated cost so far (scene_budget), checked before each thing is built.
struct cost {
  const scene_budget& budget;
  std::size_t vertices = 0, particles = 0, lights = 0;
  std::size_t texels = 0, array_bytes = 0;  // glTF assets' textures as read, and the array they make (material_textures.hpp)
  void add(std::size_t v, std::size_t p, std::size_t l, const std::string& where, std::size_t texel_bytes = 0) {
    vertices += v;
    particles += p;
    lights += l;
    texels += texel_bytes;
    const std::size_t bytes = used();
    if (bytes > budget.bytes)
      throw bad_field{where + ": the scene would take about " + mib(bytes) + " MiB by here (" + std::to_string(vertices) +
                      " vertices, " + std::to_string(particles) + " particles, " + std::to_string(lights) +
                      " lights), over the budget of " + mib(budget.bytes) + " MiB (--budget MIB raises it)"};
  }
  std::size_t used() const {
    return vertices * bytes_per_vertex + particles * bytes_per_particle + lights * bytes_per_light + texels;
  }
  std::size_t left() const { return budget.bytes - std::min(used(), budget.bytes); }
};

// The vertices detail::revolve makes of a profile of `points` points turned in `slices` slices.
std::size_t revolved(std::size_t points, int slices) { return points * std::size_t(slices + 1); }

material read_material(reader& r) {
  material m;
  m.diffuse = r.vec<3>("diffuse", m.diffuse, 0.0f, 1.0f);
  m.alpha = r.number("alpha", 1.0f, 0.0f, 1.0f);
  m.spec_intensity = r.number("spec_intensity", 0.0f, 0.0f, 1.0f);
  m.spec_power = r.number("spec_power", 16.0f, 0.0f, 255.0f);
  m.refractive = r.boolean("refractive", false);
  m.hair = r.boolean("hair", false);
  r.finish();
  return m;
}

// An object's "position", then its turn of "rotation_y" degrees about y, then "rotation_x" about x.
glm::mat4 placement(reader& r) {
  const glm::vec3 position = r.vec<3>("position", glm::vec3(0.0f), -big, big);
  const float yaw = r.number("rotation_y", 0.0f, -360.0f, 360.0f), pitch = r.number("rotation_x", 0.0f, -360.0f, 360.0f);
  return glm::rotate(glm::rotate(glm::translate(glm::mat4(1.0f), position), glm::radians(yaw), glm::vec3(0, 1, 0)),
                     glm::radians(pitch), glm::vec3(1, 0, 0));
}

object read_object(reader& r, const std::map<std::string, std::uint32_t>& materials, cost& spent) {
  object o;
  const std::string kind = r.text("shape");
  const std::string name = r.text("material");
  const auto it = materials.find(name);
  if (it == materials.end()) throw bad_field{r.field("material") + ": unknown material '" + name + "'"};
  o.material = it->second;
  const float tiny = 1e-4f;
  auto segments = [&] { return int(r.integer("segments", 32, 3, 512)); };
  // Each shape's vertices are counted (spent.add) before it is built.
  const std::string where = r.field("shape");
  if (kind == "box" || kind == "room") {
    const glm::vec3 size = r.vec<3>("size", tiny, big);
    spent.add(24, 0, 0, where);
    o.geometry = kind == "box" ? shape_box(size) : shape_room(size);
  } else if (kind == "pane") {
    const glm::vec2 size = r.vec<2>("size", tiny, big);
    spent.add(4, 0, 0, where);
    o.geometry = shape_pane(size);
  } else if (kind == "sphere") {
    const float radius = r.number("radius", tiny, big);
    const int n = segments();
    spent.add(revolved(std::size_t(std::max(n / 2, 2) + 1), n), 0, 0, where);
    o.geometry = shape_sphere(radius, n);
  } else if (kind == "cylinder" || kind == "bottle") {
    const float radius = r.number("radius", tiny, big), height = r.number("height", tiny, big);
    const int n = segments();
    spent.add(revolved(kind == "cylinder" ? 6 : 9, n), 0, 0, where);
    o.geometry = kind == "cylinder" ? shape_cylinder(radius, height, n) : shape_bottle(radius, height, n);
  } else if (kind == "hair") {
    const float radius = r.number("radius", tiny, big), length = r.number("length", tiny, big);
    const int strands = int(r.integer("strands", 1, 100000));
    const float width = r.number("width", 0.01f, tiny, big);
    const int pieces = int(r.integer("segments", 8, 1, 64));
    const auto seed = std::uint32_t(r.integer("seed", 1, 0, 1000000000));
    spent.add(std::size_t(strands) * std::size_t(pieces) * 8u, 0, 0, where);  // two crossed quads a piece
    o.geometry = shape_hair(radius, strands, length, width, pieces, seed);
  } else {
    throw bad_field{r.field("shape") + ": unknown shape '" + kind + "' (box, room, pane, sphere, cylinder, bottle, hair)"};
  }
  o.transform = placement(r);
  r.finish();
  return o;
}

// An object that is a glTF asset (scene_gltf.hpp), its path relative to the scene file's folder: its meshes
// and materials, placed by the object's position and turns and scaled by its "scale"; its cameras and
// lights are not the scene's.
void add_asset(reader& r, const std::string& scene_file, scene& s, cost& spent) {
  std::filesystem::path file(r.text("gltf"));
  if (file.is_relative()) file = std::filesystem::path(scene_file).parent_path() / file;
  const float scale = r.number("scale", 1.0f, 1e-6f, big);
  const glm::mat4 place = glm::scale(placement(r), glm::vec3(scale));
  r.finish();
  auto asset = load_gltf(file.string(), scene_budget{spent.left(), spent.budget.file_bytes});
  if (!asset) throw bad_field{r.field("gltf") + ": " + asset.error()};
  const auto first = std::uint32_t(s.materials.size());
  const int first_texture = int(s.textures.size());
  for (material& m : asset->materials)
    if (m.texture >= 0) m.texture += first_texture;
  s.materials.insert(s.materials.end(), asset->materials.begin(), asset->materials.end());
  std::size_t texel_bytes = 0;
  for (texture& t : asset->textures) {
    texel_bytes += t.rgba.size();
    s.textures.push_back(std::move(t));
  }
  // The array of every texture of the scene so far, resampled to the largest, grows with each asset's.
  const std::size_t array_bytes = s.textures.empty() ? 0 : texture_array_bytes(s);
  spent.add(0, 0, 0, r.field("gltf"), texel_bytes + array_bytes - spent.array_bytes);
  spent.array_bytes = array_bytes;
  for (object& o : asset->objects) {
    spent.add(o.geometry.positions.size(), 0, 0, r.field("gltf"));
    o.material += first;
    o.transform = place * o.transform;
    if (!finite_in_world(o.geometry, o.transform)) throw bad_field{r.field("scale") + ": places the asset past the float range"};
    s.objects.push_back(std::move(o));
  }
}

light read_light(reader& r) {
  light l;
  const std::string kind = r.text("type");
  if (kind == "directional") l.kind = light_kind::directional;
  else if (kind == "point") l.kind = light_kind::point;
  else if (kind == "spot") l.kind = light_kind::spot;
  else throw bad_field{r.field("type") + ": unknown light type '" + kind + "' (directional, point, spot)"};
  l.colour = r.vec<3>("colour", l.colour, 0.0f, big);
  l.intensity = r.number("intensity", 1.0f, 0.0f, big);
  if (l.kind != light_kind::directional) l.position = r.vec<3>("position", -big, big);
  if (l.kind != light_kind::point) {
    l.direction = r.vec<3>("direction", -big, big);
    if (glm::length(l.direction) < 1e-6f) throw bad_field{r.field("direction") + ": must not be zero"};
    l.direction = glm::normalize(l.direction);
  }
  if (l.kind != light_kind::directional) l.range = r.number("range", 1e-3f, big);
  if (l.kind == light_kind::spot) {
    l.outer_angle = r.number("outer_angle", 30.0f, 0.0f, 90.0f);
    l.inner_angle = r.number("inner_angle", l.outer_angle, 0.0f, l.outer_angle);
  }
  l.shadows = r.boolean("shadows", false);
  r.finish();
  return l;
}

particle_system read_particles(reader& r, const std::map<std::string, std::uint32_t>& materials, cost& spent) {
  particle_system ps;
  const std::string name = r.text("material");
  const auto it = materials.find(name);
  if (it == materials.end()) throw bad_field{r.field("material") + ": unknown material '" + name + "'"};
  ps.material = it->second;
  const float tiny = 1e-4f;
  ps.base = r.vec<3>("base", -big, big);
  ps.radius = r.number("radius", ps.radius, tiny, big);
  ps.height = r.number("height", ps.height, 0.0f, big);
  ps.size = r.number("size", ps.size, tiny, big);
  ps.count = int(r.integer("count", ps.count, 0, 1000000));
  ps.seed = std::uint32_t(r.integer("seed", 1, 0, 1000000000));
  spent.add(0, std::size_t(ps.count), 0, r.field("count"));
  r.finish();
  return ps;
}

post_effect read_post(reader& r) {
  post_effect e;
  const std::string kind = r.text("effect");
  const post_kind kinds[] = {post_kind::blur, post_kind::bloom, post_kind::depth_of_field, post_kind::greyscale,
                             post_kind::sepia, post_kind::antialias};
  bool known = false;
  for (post_kind k : kinds)
    if (kind == post_name(k)) {
      e.kind = k;
      known = true;
    }
  if (!known) throw bad_field{r.field("effect") + ": unknown effect '" + kind + "' (blur, bloom, dof, greyscale, sepia, aa)"};
  if (e.kind == post_kind::blur || e.kind == post_kind::bloom || e.kind == post_kind::depth_of_field) {
    e.radius = int(r.integer("radius", e.radius, 0, 64));
    e.sigma = r.number("sigma", e.sigma, 0.0f, 64.0f);
  }
  if (e.kind == post_kind::bloom) {
    e.threshold = r.number("threshold", e.threshold, 0.0f, big);
    e.intensity = r.number("intensity", e.intensity, 0.0f, big);
  }
  if (e.kind == post_kind::depth_of_field) {
    e.focus = r.number("focus", e.focus, 0.0f, big);
    e.range = r.number("range", e.range, 0.0f, big);
  }
  if (e.kind == post_kind::antialias) {
    e.normal_scale = r.number("normal_scale", e.normal_scale, 0.0f, big);
    e.depth_scale = r.number("depth_scale", e.depth_scale, 0.0f, big);
    e.interlace = r.boolean("interlace", e.interlace);
    e.strength = r.number("strength", e.strength, 0.0f, 1.0f);
  }
  r.finish();
  return e;
}

std::vector<post_effect> read_post_chain(const json& chain, const std::string& path) {
  if (!chain.is_array()) throw bad_field{path + ": expected an array"};
  std::vector<post_effect> out;
  for (std::size_t i = 0; i < chain.size(); ++i) {
    reader e(chain[i], path + "[" + std::to_string(i) + "]");
    out.push_back(read_post(e));
  }
  return out;
}

}  // namespace

result<std::vector<post_effect>> parse_post_chain(const std::string& text, const std::string& name) {
  try {
    const json root = parse_bounded<json>(text);
    reader top(root, "");
    auto chain = read_post_chain(top.raw("post"), "post");
    top.finish();
    return chain;
  } catch (const json::exception& e) {
    return failure{name + ": not valid JSON: " + parse_message(e)};
  } catch (const json_too_big& e) {
    return failure{name + ": not a scene file: its JSON is " + e.message};
  } catch (const bad_field& e) {
    return failure{name + ": " + e.message};
  }
}

result<scene> parse_scene(const std::string& text, const std::string& name, const scene_budget& budget) {
  try {
    const json root = parse_bounded<json>(text);
    reader top(root, "");
    scene s;
    cost spent{budget};
    {
      reader c(top.raw("camera"), "camera");
      s.view.position = c.vec<3>("position", -big, big);
      s.view.target = c.vec<3>("target", -big, big);
      if (glm::length(s.view.target - s.view.position) < 1e-6f) throw bad_field{"camera.target: must differ from camera.position"};
      s.view.fov_y = c.number("fov_y", 60.0f, 1.0f, 179.0f);
      s.view.near_plane = c.number("near", 0.1f, 1e-4f, big);
      s.view.far_plane = c.number("far", 100.0f, s.view.near_plane * 1.001f, big);
      c.finish();
    }
    s.ambient = top.vec<3>("ambient", s.ambient, 0.0f, 1.0f);
    std::map<std::string, std::uint32_t> materials;
    const json& mats = top.raw("materials");
    if (!mats.is_object() || mats.empty()) throw bad_field{"materials: expected an object with at least one material"};
    for (const auto& [key, value] : mats.items()) {
      reader m(value, "materials." + key);
      materials[key] = std::uint32_t(s.materials.size());
      s.materials.push_back(read_material(m));
    }
    const json& objs = top.raw("objects");
    if (!objs.is_array() || objs.empty()) throw bad_field{"objects: expected an array with at least one object"};
    for (std::size_t i = 0; i < objs.size(); ++i) {
      reader o(objs[i], "objects[" + std::to_string(i) + "]");
      if (objs[i].contains("gltf")) add_asset(o, name, s, spent);
      else s.objects.push_back(read_object(o, materials, spent));
    }
    if (top.has("lights")) {
      const json& lights = root["lights"];
      if (!lights.is_array()) throw bad_field{"lights: expected an array"};
      for (std::size_t i = 0; i < lights.size(); ++i) {
        reader l(lights[i], "lights[" + std::to_string(i) + "]");
        spent.add(0, 0, 1, "lights[" + std::to_string(i) + "]");
        s.lights.push_back(read_light(l));
      }
    }
    if (top.has("particles")) {
      const json& systems = root["particles"];
      if (!systems.is_array()) throw bad_field{"particles: expected an array"};
      for (std::size_t i = 0; i < systems.size(); ++i) {
        reader p(systems[i], "particles[" + std::to_string(i) + "]");
        s.particles.push_back(read_particles(p, materials, spent));
      }
    }
    if (top.has("post")) s.post = read_post_chain(root["post"], "post");
    top.finish();
    return s;
  } catch (const json::exception& e) {
    return failure{name + ": not valid JSON: " + parse_message(e)};
  } catch (const json_too_big& e) {
    return failure{name + ": not a scene file: its JSON is " + e.message};
  } catch (const bad_field& e) {
    return failure{name + ": " + e.message};
  }
}

result<std::string> read_input_file(const std::string& path, const char* what, std::size_t limit) {
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) return failure{path + ": cannot read the " + what + ": " + std::strerror(errno)};
  if (S_ISDIR(st.st_mode)) return failure{path + ": a folder, not a " + what};
  if (!S_ISREG(st.st_mode)) return failure{path + ": not a plain file, so not read as a " + what};
  if (std::size_t(st.st_size) > limit)
    return failure{path + ": " + std::to_string(st.st_size) + " bytes, more than a " + what + " may have (" +
                   std::to_string(limit) + ")"};
  std::ifstream in(path, std::ios::binary);
  if (!in) return failure{path + ": cannot read the " + what};
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string mib(std::size_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20); }

result<scene> load_scene(const std::string& path, const scene_budget& budget) {
  if (is_gltf_path(path)) return load_gltf(path, budget);
  auto text = read_input_file(path, "scene file", budget.file_bytes);
  if (!text) return failure{text.error()};
  return parse_scene(*text, path, budget);
}

std::size_t scene_bytes(const scene& s) {
  std::size_t vertices = 0, particles = 0;
  for (const object& o : s.objects) vertices += o.geometry.positions.size();
  for (const particle_system& p : s.particles) particles += std::size_t(std::max(p.count, 0));
  std::size_t texels = 0;
  for (const texture& t : s.textures) texels += t.rgba.size();
  if (!s.textures.empty()) texels += texture_array_bytes(s);
  return vertices * bytes_per_vertex + particles * bytes_per_particle + s.lights.size() * bytes_per_light + texels;
}

result<std::vector<post_effect>> load_post_chain(const std::string& path) {
  auto text = read_input_file(path, "post-processing chain", scene_budget{}.file_bytes);
  if (!text) return failure{text.error()};
  return parse_post_chain(*text, path);
}

}  // namespace dstrans

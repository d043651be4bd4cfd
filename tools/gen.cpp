// dstrans gen: prints the GLSL that the templates generate, ready for glslangValidator as it is.
#include <cstdio>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <dstrans/dstrans.hpp>

#include "cli.hpp"
#include "output_dir.hpp"
#include <dstrans/frame/passes.hpp>
#include "scene_json.hpp"

namespace dstrans::cli {

namespace {

const char* const usage =
    "usage: dstrans gen gbuffer <layout> [--side write|read|both] [--first-location N] [--first-binding N]\n"
    "                                  [--glsl-version V]\n"
    "       dstrans gen interlace <predicate> [--glsl-version V]\n"
    "       dstrans gen pipeline <scene.json|.gltf|.glb> [--out DIR]   every shader the scene's pipeline compiles; with\n"
    "                                       --out one file each (<pass>.vert, <pass>.frag), else all printed\n"
    "layouts:    thesis (Table 3.1), compact (8 bytes, depth from the attachment), light (Table 3.2),\n"
    "            light-rgb (8 bytes, RGB specular), shadow (Table 3.3)\n"
    "predicates: rows (the thesis's), columns, checker, none\n"
    "versions:   330, 410 (samplers by name: set their units with glUniform1i), 450 (the default), vulkan\n";

struct named_layout {
  int targets;
  std::function<void(glsl::source&, const glsl::layout_options&)> add;
};

// Layout L under `name`, the name the passes use for it.
template <class L>
named_layout entry(const char* name) {
  return {L::target_count, [name](glsl::source& s, const glsl::layout_options& o) { glsl::add_layout<L>(s, name, o); }};
}

const std::map<std::string, named_layout>& layouts() {
  static const std::map<std::string, named_layout> table{
      {"thesis", entry<thesis_gbuffer>("gbuffer")},
      {"compact", entry<compact_gbuffer>("gbuffer")},
      {"light", entry<thesis_light_buffer>("light")},
      {"light-rgb", entry<rgb_light_buffer>("light")},
      {"shadow", entry<thesis_shadow_map>("shadow")},
  };
  return table;
}

const std::map<std::string, std::function<void(glsl::source&)>>& predicates() {
  static const std::map<std::string, std::function<void(glsl::source&)>> table{
      {"rows", [](glsl::source& s) { glsl::add_interlace<interlace::rows>(s); }},
      {"columns", [](glsl::source& s) { glsl::add_interlace<interlace::columns>(s); }},
      {"checker", [](glsl::source& s) { glsl::add_interlace<interlace::checker>(s); }},
      {"none", [](glsl::source& s) { glsl::add_interlace<interlace::none>(s); }},
  };
  return table;
}

template <class Table>
const typename Table::mapped_type& pick(const Table& table, const std::string& key, const std::string& what) {
  const auto it = table.find(key);
  if (it == table.end()) {
    std::string known;
    for (const auto& [name, fn] : table) known += (known.empty() ? "" : ", ") + name;
    throw usage_error{"unknown " + what + " '" + key + "' (known: " + known + ")"};
  }
  return it->second;
}

// The shaders of the scene in `file`'s pipeline, printed or written into `out` (pipeline.json lists them).
int gen_pipeline(const std::string& file, const std::string& out) {
  std::optional<output_dir> dir;
  if (!out.empty()) {
    auto d = output_dir::open(out, "pipeline.json");
    if (!d) {
      std::fprintf(stderr, "dstrans gen: %s\n", d.error().c_str());
      return 1;
    }
    dir.emplace(std::move(*d));
  }
  const auto s = load_scene(file);
  if (!s) {
    std::fprintf(stderr, "dstrans gen: %s\n", s.error().c_str());
    return 1;
  }
  const render::options o;
  const auto passes = render::pipeline_passes(pass_shaders(), *s, render::plan_of(*s, o), o);
  if (!passes) {
    std::fprintf(stderr, "dstrans gen: %s\n", passes.error().c_str());
    return 1;
  }
  for (const render::named_pass& p : *passes) {
    std::string stem = p.name;
    for (char& c : stem) c = c == ' ' ? '_' : c;
    for (const auto& [stage, src] : {std::make_pair(".vert", &p.sources.vertex), std::make_pair(".frag", &p.sources.fragment)}) {
      if (!dir) {
        std::printf("// ---- %s%s\n%s\n", stem.c_str(), stage, src->str().c_str());
        continue;
      }
      if (auto ok = dir->add(stem + stage, src->str()); !ok) {
        std::fprintf(stderr, "dstrans gen: %s\n", ok.error().c_str());
        return 1;
      }
    }
  }
  if (!dir) return 0;
  if (auto ok = dir->commit(); !ok) {
    std::fprintf(stderr, "dstrans gen: %s\n", ok.error().c_str());
    return 1;
  }
  std::printf("dstrans gen: %zu shaders in %s\n", 2 * passes->size(), out.c_str());
  return 0;
}

glsl::side parse_side(const std::string& s) {
  if (s == "write") return glsl::side::write;
  if (s == "read") return glsl::side::read;
  if (s == "both") return glsl::side::both;
  throw usage_error{"--side must be write, read or both, not '" + s + "'"};
}

}  // namespace

int gen(std::vector<std::string> args) {
  if (!args.empty() && (args[0] == "--help" || args[0] == "-h")) {
    std::fputs(usage, stdout);
    return 0;
  }
  try {
    const std::string side = take_option(args, "--side", ""), location = take_option(args, "--first-location", ""),
                      binding = take_option(args, "--first-binding", ""), out = take_option(args, "--out", ""),
                      version_name = take_option(args, "--glsl-version", "450");
    args = operands(args);
    const result<glsl::version> version = glsl::version_named(version_name);
    if (!version) throw usage_error{version.error()};
    if (args.size() == 2 && args[0] == "pipeline") {
      if (!(side + location + binding).empty()) throw usage_error{"gen pipeline takes only --out"};
      if (*version != glsl::version::glsl450) throw usage_error{"gen pipeline writes dstrans's own passes, which are GLSL 450"};
      return gen_pipeline(args[1], out);
    }
    if (!out.empty()) throw usage_error{"--out goes with gen pipeline"};
    if (args.size() != 2) throw usage_error{"gen takes a kind and a name"};
    glsl::source src(*version);
    if (args[0] == "gbuffer") {
      const named_layout& l = pick(layouts(), args[1], "layout");
      glsl::layout_options opt;
      if (!side.empty()) opt.sides = parse_side(side);
      // Outputs must fit the 8 locations every GL 4.5 and Vulkan device has.
      if (!location.empty()) opt.first_location = to_int(location, 0, 8 - l.targets, "--first-location");
      if (!binding.empty()) opt.first_binding = to_int(binding, 0, 64 - l.targets, "--first-binding");
      l.add(src, opt);
    } else if (args[0] == "interlace") {
      if (!(side + location + binding).empty()) throw usage_error{"gen interlace takes only --glsl-version"};
      pick(predicates(), args[1], "interlace predicate")(src);
    }
    else throw usage_error{"unknown kind '" + args[0] + "' (known: gbuffer, interlace, pipeline)"};
    std::fputs(src.str().c_str(), stdout);
    return 0;
  } catch (const usage_error& e) {
    std::fprintf(stderr, "dstrans gen: %s\n%s", e.message.c_str(), usage);
    return 2;
  }
}

}  // namespace dstrans::cli

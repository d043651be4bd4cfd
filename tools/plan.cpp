// dstrans plan: the effects a scene calls for and why, and the passes, render targets and shader switches
// of the pipeline they need. dstrans gen pipeline (gen.cpp) prints that pipeline's shaders.
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <dstrans/scene_features.hpp>

#include "cli.hpp"
#include <dstrans/frame/plan.hpp>
#include "scene_json.hpp"

namespace dstrans::cli {

namespace {

using json = nlohmann::ordered_json;

const char* const usage =
    "usage: dstrans plan <scene.json|.gltf|.glb> [--json] [--budget MIB] [--temporal on|off]\n"
    "       [--rough-refraction on|off]\n"
    "the effects the scene calls for (and why), and the passes, render targets and shader switches of the\n"
    "interlaced deferred pipeline that runs exactly those effects, and a frame's passes in the order they run;\n"
    "--temporal on: with temporal interlacing (the previous frame's targets, where the scene has glass);\n"
    "--rough-refraction on: with the compose pass's blur of refraction through rough glass\n";

std::string joined(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : ", ") + w;
  return out.empty() ? "-" : out;
}

}  // namespace

int plan(std::vector<std::string> args) {
  if (!args.empty() && (args[0] == "--help" || args[0] == "-h")) {
    std::fputs(usage, stdout);
    return 0;
  }
  try {
    const bool as_json = take_flag(args, "--json");
    const scene_budget budget = take_budget(args);
    render::options o;
    o.temporal = take_on_off(args, "--temporal", false);
    o.rough_refraction = take_on_off(args, "--rough-refraction", false);
    const std::vector<std::string> files = operands(args);
    if (files.size() != 1) throw usage_error{"plan takes one scene file, not " + std::to_string(files.size()) + " arguments"};
    const auto s = load_scene(files[0], budget);
    if (!s) {
      std::fprintf(stderr, "dstrans plan: %s\n", s.error().c_str());
      return 1;
    }
    const std::vector<feature> found = scene_features(*s);
    const render::frame_plan frame = render::plan_of(*s, o);
    const pipeline_plan& p = frame.pipeline;
    const frame_schedule schedule = render::schedule_of(*s, frame, o);
    if (as_json) {
      json reasons = json::object(), passes = json::array(), targets = json::array();
      for (const feature& f : found) reasons[effect_name(f.what)] = f.why;
      for (const planned_pass& pass : p.passes)
        passes.push_back({{"name", pass.name}, {"targets", pass.writes}, {"reads", pass.reads}, {"switches", pass.switches}});
      for (const planned_target& t : p.targets)
        targets.push_back({{"name", t.name}, {"format", t.format}, {"bytes_per_pixel", t.bytes_per_pixel},
                           {"size", t.shadow_map ? "shadow map" : t.volume ? "volume atlas" : "screen"}});
      json frame_passes = json::array();
      for (const scheduled_pass& pass : schedule.passes)
        frame_passes.push_back({{"pass", pass.timer}, {"label", pass.label}, {"kind", pass_kind_name(pass.kind)},
                                {"light", pass.light}, {"reads", pass.reads}, {"writes", pass.writes}});
      const json out{{"effects", p.on.names()}, {"reasons", reasons}, {"passes", passes}, {"targets", targets},
                     {"bytes_per_pixel", p.bytes_per_pixel}, {"schedule", frame_passes}};
      std::puts(out.dump().c_str());
      return 0;
    }
    std::printf("effects:\n");
    if (found.empty()) std::printf("  none: a plain deferred renderer\n");
    for (const feature& f : found) std::printf("  %-20s %s\n", effect_name(f.what), f.why.c_str());
    std::printf("passes:\n");
    for (const planned_pass& pass : p.passes)
      std::printf("  %-8s reads %s; writes %s; switches %s\n", pass.name.c_str(), joined(pass.reads).c_str(),
                  joined(pass.writes).c_str(), joined(pass.switches).c_str());
    std::printf("targets:\n");
    for (const planned_target& t : p.targets)
      std::printf("  %-21s %-8s %3d bytes a %s\n", t.name.c_str(), t.format.c_str(), t.bytes_per_pixel,
                  t.shadow_map ? "shadow-map texel" : t.volume ? "volume-atlas texel" : "pixel");
    std::printf("%d bytes a pixel on screen\n", p.bytes_per_pixel);
    std::printf("a frame, in order:\n");
    for (const scheduled_pass& pass : schedule.passes)
      std::printf("  %-36s %-12s reads %s; writes %s\n", pass.label.c_str(), pass_kind_name(pass.kind),
                  joined(pass.reads).c_str(), joined(pass.writes).c_str());
    return 0;
  } catch (const usage_error& e) {
    std::fprintf(stderr, "dstrans plan: %s\n%s", e.message.c_str(), usage);
    return 2;
  }
}

}  // namespace dstrans::cli

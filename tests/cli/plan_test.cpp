// dstrans plan and dstrans gen pipeline end to end: a scene without glass plans a plain deferred
// pipeline, and each step of the ladder (a pane, a refractive pane, a spot light that sees it) adds
// exactly its effect's switches and targets; every shader gen pipeline writes compiles as it is (the
// camera stands within the spot light's reach, so its light pass is the full-screen variant).
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include "../effect_scenes.hpp"
#include "run_tool.hpp"

using json = nlohmann::ordered_json;
using dstrans::testing::minus;

namespace {

// The ladder of tests/effect_scenes.hpp as a scene file: `glass` adds a pane out of the spot light's cone,
// `refractive` makes it refract, `seen` turns the spot light to it.
std::string ladder_scene(bool glass, bool refractive, bool seen) {
  const std::string pane = glass ? R"(, {"shape": "pane", "size": [1.2, 1.0], "position": [-1.2, 1.0, 0.5], "material": "glass"})" : "";
  const std::string direction = seen ? "[-3.2, -2.0, 0.5]" : "[-0.5, -3.0, -1.0]";
  const std::string path = std::string(DSTRANS_TEST_DIR) + "/ladder_" + std::to_string(glass) + std::to_string(refractive) +
                           std::to_string(seen) + ".json";
  std::ofstream(path) << R"({"camera": {"position": [0, 1.5, 5], "target": [0, 1, 0]},
    "materials": {"floor": {"diffuse": [0.8, 0.8, 0.8]},
                  "glass": {"diffuse": [0.2, 0.5, 1.0], "alpha": 0.4, "refractive": )"
                      << (refractive ? "true" : "false") << R"(}},
    "objects": [{"shape": "box", "size": [8, 0.02, 8], "position": [0, 0.01, 0], "material": "floor"})"
                      << pane << R"(],
    "lights": [{"type": "spot", "position": [2, 3, 0], "direction": )"
                      << direction << R"(, "range": 8, "inner_angle": 15, "outer_angle": 25, "shadows": true}]})";
  return path;
}

struct plan_facts {
  std::set<std::string> effects, switches, targets;
};

plan_facts plan_of(const std::string& scene, const std::string& options = "") {
  const auto r = run("plan " + scene + " --json" + options, "");
  INFO(r.out);
  REQUIRE(r.status == 0);
  const json p = json::parse(r.out);
  plan_facts f;
  for (const json& e : p["effects"]) f.effects.insert(e.get<std::string>());
  for (const json& pass : p["passes"])
    for (const json& s : pass["switches"]) f.switches.insert(pass["name"].get<std::string>() + ": " + s.get<std::string>());
  for (const json& t : p["targets"]) f.targets.insert(t["name"].get<std::string>());
  return f;
}

}  // namespace

TEST_CASE("plan --json: plain deferred without glass, then exactly one effect more per step", "[cli][plan]") {
  const plan_facts plain = plan_of(ladder_scene(false, false, false)), pane = plan_of(ladder_scene(true, false, false)),
                   refractive = plan_of(ladder_scene(true, true, false)), seen = plan_of(ladder_scene(true, true, true));
  CHECK(plain.effects == std::set<std::string>{"shadows"});
  CHECK(plain.switches == std::set<std::string>{"shadow: DST_SHADOWS", "light: DST_SHADOWS"});
  CHECK_FALSE(plain.targets.count("shadow.colour"));
  CHECK(minus(pane.effects, plain.effects) == std::set<std::string>{"transparency"});
  CHECK(minus(pane.switches, plain.switches) == std::set<std::string>{"gbuffer: DST_TRANSPARENCY", "compose: DST_TRANSPARENCY"});
  CHECK(pane.targets == plain.targets);
  CHECK(minus(refractive.effects, pane.effects) == std::set<std::string>{"refraction"});
  CHECK(minus(refractive.switches, pane.switches) == std::set<std::string>{"compose: DST_REFRACTION"});
  CHECK(refractive.targets == pane.targets);
  CHECK(minus(seen.effects, refractive.effects) == std::set<std::string>{"transparent_shadows"});
  CHECK(minus(seen.switches, refractive.switches) ==
        std::set<std::string>{"shadow: DST_TRANSPARENT_SHADOWS", "light: DST_TRANSPARENT_SHADOWS"});
  CHECK(minus(seen.targets, refractive.targets) == std::set<std::string>{"shadow.colour"});
  for (const plan_facts* f : {&plain, &pane, &refractive}) CHECK(minus(f->switches, seen.switches).empty());
}

TEST_CASE("plan --temporal on: the previous frame's targets and the compose switch, only where there is glass", "[cli][plan]") {
  const plan_facts pane = plan_of(ladder_scene(true, false, false)), temporal = plan_of(ladder_scene(true, false, false), " --temporal on");
  CHECK(minus(temporal.targets, pane.targets) ==
        std::set<std::string>{"previous.gbuffer.RT0", "previous.gbuffer.RT1", "previous.gbuffer.RT2", "previous.gbuffer.RT3",
                              "previous.light.RT0"});
  CHECK(minus(temporal.switches, pane.switches) == std::set<std::string>{"compose: DST_TEMPORAL"});
  const plan_facts plain = plan_of(ladder_scene(false, false, false));
  CHECK(plan_of(ladder_scene(false, false, false), " --temporal on").targets == plain.targets);
  CHECK_THAT(run("plan " + ladder_scene(true, false, false) + " --temporal on", "").out, Catch::Contains("40 bytes a pixel on screen"));
  const auto bad = run("plan " + ladder_scene(true, false, false) + " --temporal maybe", "");
  CHECK(bad.status == 2);
  CHECK_THAT(bad.out, Catch::Contains("--temporal must be on or off, not 'maybe'"));
}

TEST_CASE("plan --rough-refraction on: the compose switch where glass refracts, nothing more", "[cli][plan]") {
  const plan_facts refractive = plan_of(ladder_scene(true, true, false)),
                   rough = plan_of(ladder_scene(true, true, false), " --rough-refraction on");
  CHECK(minus(rough.switches, refractive.switches) == std::set<std::string>{"compose: DST_ROUGH_REFRACTION"});
  CHECK(rough.targets == refractive.targets);
  // Glass that does not refract has no refracted sample to blur.
  const plan_facts pane = plan_of(ladder_scene(true, false, false));
  CHECK(plan_of(ladder_scene(true, false, false), " --rough-refraction on").switches == pane.switches);
  const auto bad = run("plan " + ladder_scene(true, true, false) + " --rough-refraction blurry", "");
  CHECK(bad.status == 2);
  CHECK_THAT(bad.out, Catch::Contains("--rough-refraction must be on or off, not 'blurry'"));
}

TEST_CASE("plan --json lists a frame's passes in order, each light's among them", "[cli][plan]") {
  const auto r = run("plan " + ladder_scene(true, true, true) + " --json", "");
  REQUIRE(r.status == 0);
  const json p = json::parse(r.out);
  std::vector<std::string> order;
  for (const json& pass : p["schedule"]) order.push_back(pass["label"].get<std::string>());
  CHECK(order == std::vector<std::string>{"gbuffer pass", "shadow pass, light 0", "light pass, light 0", "compose pass"});
}

TEST_CASE("plan explains itself in words, and refuses bad input", "[cli][plan]") {
  const auto r = run("plan " + ladder_scene(true, false, false), "");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("transparency         objects[1] has material 1 with alpha 0.4"));
  CHECK_THAT(r.out, Catch::Contains("20 bytes a pixel on screen"));
  CHECK_THAT(r.out, Catch::Contains("a frame, in order:\n  gbuffer pass "));
  CHECK_THAT(r.out, Catch::Contains("shadow pass, light 0"));
  CHECK(run("plan", "").status == 2);
  CHECK(run("plan a.json --fast", "").status == 2);
  const auto missing = run("plan /nonexistent/scene.json", "");
  CHECK(missing.status == 1);
  CHECK_THAT(missing.out, Catch::Contains("/nonexistent/scene.json"));
}

TEST_CASE("gen pipeline writes each shader of the plan, each accepted by glslangValidator", "[cli][plan]") {
  const std::string out = std::string(DSTRANS_TEST_DIR) + "/pipeline_seen";
  std::filesystem::remove_all(out);
  const auto r = run("gen pipeline " + ladder_scene(true, true, true) + " --out " + out, "");
  INFO(r.out);
  REQUIRE(r.status == 0);
  std::set<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(out)) {
    if (e.path().filename() == "pipeline.json") continue;  // the list of what gen wrote, checked below
    names.insert(e.path().filename().string());
    const std::string cmd = std::string(GLSLANG_VALIDATOR) + " " + e.path().string() + " > /dev/null";
    INFO(e.path());
    CHECK(std::system(cmd.c_str()) == 0);
  }
  // The ladder's one spot light is drawn as its volume mesh, wherever the camera is.
  CHECK(names == std::set<std::string>{"gbuffer_pass.vert", "gbuffer_pass.frag", "shadow_pass.vert", "shadow_pass.frag",
                                       "light_pass_transparent_shadows_volume.vert",
                                       "light_pass_transparent_shadows_volume.frag", "compose_pass.vert",
                                       "compose_pass.frag"});
  std::ifstream manifest(out + "/pipeline.json");
  REQUIRE(manifest);
  const auto listed = nlohmann::json::parse(manifest)["files"].get<std::set<std::string>>();
  names.insert("pipeline.json");
  CHECK(listed == names);
}

TEST_CASE("docs/hooks.md names every shared formula, and docs/integration.md's pictures exist", "[cli][docs]") {
  auto text_of = [](const std::string& path) {
    std::ifstream in(std::string(DSTRANS_SOURCE_DIR) + "/" + path);
    REQUIRE(in);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  const std::string hooks = text_of("docs/hooks.md"), guide = text_of("docs/integration.md");
  const json list = json::parse(run("eval --list --json", "").out);
  for (const json& f : list) {
    INFO(f["fn"]);
    CHECK(hooks.find(f["fn"].get<std::string>()) != std::string::npos);
  }
  std::size_t pictures = 0;
  for (std::size_t at = guide.find("](images/"); at != std::string::npos; at = guide.find("](images/", at + 1)) {
    const std::string file = guide.substr(at + 2, guide.find(')', at) - at - 2);
    INFO(file);
    CHECK(std::filesystem::exists(std::string(DSTRANS_SOURCE_DIR) + "/docs/" + file));
    ++pictures;
  }
  CHECK(pictures >= 5);
}

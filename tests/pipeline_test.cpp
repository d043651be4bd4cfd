// Without a GPU: the effects a scene calls for, the plan they give at compile time and at run
// time, and the pass shaders' switches resolved out of the GLSL text.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <set>

#include <dstrans/glsl.hpp>
#include <dstrans/frame/plan.hpp>
#include <dstrans/pipeline.hpp>

#include "effect_scenes.hpp"

using namespace dstrans;
using testing::effect_scene;
using testing::minus;
using testing::rung;

namespace {

// What a plan has: its target names, and each pass as "name: switch switch ...".
std::set<std::string> targets_of(const pipeline_plan& p) {
  std::set<std::string> out;
  for (const planned_target& t : p.targets) out.insert(t.name);
  return out;
}
std::set<std::string> switches_of(const pipeline_plan& p) {
  std::set<std::string> out;
  for (const planned_pass& pass : p.passes)
    for (const std::string& s : pass.switches) out.insert(pass.name + ": " + s);
  return out;
}

}  // namespace

// The compile-time plan: figures are constants, and what an absent effect needs is not there.
using plain = pipeline<effect_set<>>;
using everything = pipeline<effect_set<effect::transparency, effect::refraction, effect::shadows, effect::transparent_shadows>>;
static_assert(plain::screen_bytes_per_pixel == 20 && plain::shadow_bytes_per_texel == 0 && !plain::interlaced);
static_assert(everything::shadow_bytes_per_texel == 8 && everything::has_shadow_colour && everything::refracts);
static_assert(pipeline<effect_set<effect::shadows>>::shadow_bytes_per_texel == 4);

TEST_CASE("each rung of the ladder calls for exactly one effect more, with a reason", "[pipeline][features]") {
  const effect added[] = {effect::shadows, effect::transparency, effect::refraction, effect::transparent_shadows,
                          effect::light_volumes, effect::textures};
  CHECK(scene_features(effect_scene(rung::nothing)).empty());
  for (int i = 0; i < 6; ++i) {
    const auto before = scene_features(effect_scene(testing::all_rungs[i])), after = scene_features(effect_scene(testing::all_rungs[i + 1]));
    INFO("rung " << i + 1);
    CHECK(effects_of(after) == effects_of(before).with(added[i]));
    CHECK_FALSE(effects_of(before).has(added[i]));
    for (const feature& f : after) CHECK_FALSE(f.why.empty());
  }
  CHECK(scene_features(effect_scene(rung::seen)).back().why ==
        "lights[1] casts shadows and reaches objects[2], which is transparent");
  CHECK(scene_features(effect_scene(rung::particles)).back().why == "particles[0] draws 60 particles of material 3");
  CHECK(scene_features(effect_scene(rung::textured)).back().why == "objects[0] has material 0, which samples textures[0]");
  scene tested = effect_scene(rung::nothing);
  tested.materials[1].alpha_cutoff = 0.5f;
  tested.materials[1].alpha = 0.3f;  // alpha-tested: opaque where drawn, so not glass
  REQUIRE(scene_features(tested).size() == 1);
  CHECK(scene_features(tested)[0].what == effect::textures);
  CHECK(scene_features(tested)[0].why == "objects[1] has material 1, alpha-tested at 0.5");
  tested.materials[1].hair = true;  // hair takes its factors alone
  CHECK(effects_of(scene_features(tested)) == effect_set<effect::many_layers>::value);
}

TEST_CASE("the plans of neighbouring rungs differ by exactly the added effect's targets and switches", "[pipeline]") {
  auto plan = [](rung r) { return plan_pipeline(effects_of(scene_features(effect_scene(r)))); };
  const pipeline_plan nothing = plan(rung::nothing), shadows = plan(rung::shadows), glass = plan(rung::glass),
                      refractive = plan(rung::refractive), seen = plan(rung::seen), smoke = plan(rung::particles),
                      textured = plan(rung::textured);
  // A scene with no glass and no shadows: plain deferred shading.
  CHECK(nothing.passes.size() == 3);
  CHECK(switches_of(nothing).empty());
  CHECK(targets_of(nothing) == std::set<std::string>{"gbuffer.RT0", "gbuffer.RT1", "gbuffer.RT2", "gbuffer.RT3", "light.RT0"});
  CHECK(nothing.bytes_per_pixel == 20);
  CHECK(minus(targets_of(shadows), targets_of(nothing)) == std::set<std::string>{"shadow.depth"});
  CHECK(shadows.pass("shadow"));
  CHECK(minus(switches_of(shadows), switches_of(nothing)) == std::set<std::string>{"shadow: DST_SHADOWS", "light: DST_SHADOWS"});
  // One glass pane: interlacing in the G-buffer pass and de-interlacing in the compose pass, no target.
  CHECK(targets_of(glass) == targets_of(shadows));
  CHECK(minus(switches_of(glass), switches_of(shadows)) ==
        std::set<std::string>{"gbuffer: DST_TRANSPARENCY", "compose: DST_TRANSPARENCY"});
  CHECK(targets_of(refractive) == targets_of(glass));
  CHECK(minus(switches_of(refractive), switches_of(glass)) == std::set<std::string>{"compose: DST_REFRACTION"});
  // The spot light sees the pane: the shadow map's colour target and Eq. 3.1's lookup.
  CHECK(minus(targets_of(seen), targets_of(refractive)) == std::set<std::string>{"shadow.colour"});
  CHECK(minus(switches_of(seen), switches_of(refractive)) ==
        std::set<std::string>{"shadow: DST_TRANSPARENT_SHADOWS", "light: DST_TRANSPARENT_SHADOWS"});
  // Smoke: the light volumes' atlas (not screen-sized), the bake and the particle pass; beside the pane, the
  // two glass layers the particles draw into and the compose lays around the glass (two RGBA16F targets).
  CHECK(minus(targets_of(smoke), targets_of(seen)) == std::set<std::string>{"volume.atlas", "glass.behind", "glass.front"});
  CHECK(minus(switches_of(smoke), switches_of(seen)) ==
        std::set<std::string>{"bake: DST_LIGHT_VOLUMES", "particles: DST_LIGHT_VOLUMES", "particles: DST_AROUND_GLASS",
                              "compose: DST_AROUND_GLASS"});
  CHECK(smoke.bytes_per_pixel == seen.bytes_per_pixel + 16);
  // Textures: texture coordinates and the texel in the passes that draw the scene's surfaces, no target.
  CHECK(targets_of(textured) == targets_of(smoke));
  CHECK(minus(switches_of(textured), switches_of(smoke)) == std::set<std::string>{"gbuffer: DST_TEXTURES", "shadow: DST_TEXTURES"});
  for (const pipeline_plan* p : {&nothing, &shadows, &glass, &refractive, &seen, &smoke})
    CHECK(minus(switches_of(*p), switches_of(textured)).empty());
}

TEST_CASE("the shadow pass samples textures only where a texture can change a shadow", "[pipeline][textures]") {
  auto shadow_switches = [](const scene& s, const render::options& o = {}) {
    const render::frame_plan p = render::plan_of(s, o);
    REQUIRE(p.pipeline.pass("shadow"));
    const std::vector<std::string>& sw = p.pipeline.pass("shadow")->switches;
    CHECK(p.textured_shadows == (std::find(sw.begin(), sw.end(), "DST_TEXTURES") != sw.end()));
    CHECK(p.shadow_effects() == (p.textured_shadows ? p.on : p.on.without(effect::textures)));
    return p.textured_shadows;
  };
  // The rung's textured floor is opaque: its shadow is its depth, so only the G-buffer pass samples it.
  scene s = effect_scene(rung::textured);
  CHECK_FALSE(render::textured_shadows(s));
  CHECK_FALSE(shadow_switches(s));
  CHECK(render::plan_of(s, {}).on.has(effect::textures));
  render::options forced;
  forced.force = effects::all();
  CHECK(shadow_switches(s, forced));
  // Textured glass colours the light through it; an alpha-tested texture cuts the occluder out.
  scene glass = s;
  glass.materials[2].texture = 0;
  CHECK(shadow_switches(glass));
  scene tested = s;
  tested.materials[1].alpha_cutoff = 0.5f;
  CHECK(shadow_switches(tested));
  // A textured material no object uses changes no shadow.
  scene unused = s;
  unused.materials.push_back(glass.materials[2]);
  CHECK_FALSE(render::textured_shadows(unused));
}

TEST_CASE("rough refraction is planned only where a deferred technique refracts", "[pipeline][refraction]") {
  const scene refractive = effect_scene(rung::refractive), glass = effect_scene(rung::glass);
  render::options o;
  o.rough_refraction = true;
  auto rough = [](const scene& s, const render::options& with) {
    const render::frame_plan p = render::plan_of(s, with);
    const planned_pass* compose = p.pipeline.pass("compose");
    REQUIRE(compose);
    const bool planned = std::count(compose->switches.begin(), compose->switches.end(), "DST_ROUGH_REFRACTION") == 1;
    CHECK(planned == render::rough_refraction(with, p.on));
    return planned;
  };
  for (render::technique t : {render::technique::interlaced, render::technique::peeling, render::technique::forward,
                              render::technique::forward_depth}) {
    o.method = t;
    INFO(render::technique_name(t));
    // Forward rendering's blend has no exponent to read the roughness back from.
    CHECK(rough(refractive, o) == !render::is_forward(t));
    CHECK_FALSE(rough(glass, o));  // glass that does not refract
    render::options off = o;
    off.rough_refraction = false;
    CHECK_FALSE(rough(refractive, off));
  }
}

TEST_CASE("the run-time plan of a set is the compile-time plan of that set", "[pipeline]") {
  const pipeline_plan a = plan_pipeline(effect_set<effect::transparency, effect::shadows>::value);
  const pipeline_plan b = pipeline<effect_set<effect::transparency, effect::shadows>>::plan();
  CHECK(targets_of(a) == targets_of(b));
  CHECK(switches_of(a) == switches_of(b));
  CHECK(a.on == b.on);
  // A set missing what an effect depends on is completed.
  CHECK(plan_pipeline(effect_set<effect::refraction>::value).on == effect_set<effect::transparency, effect::refraction>::value);
  CHECK(plan_pipeline(effect_set<effect::transparent_shadows>::value).on ==
        effect_set<effect::shadows, effect::transparent_shadows>::value);
}

TEST_CASE("a spot light's cone reaches an object by its bounding sphere", "[pipeline][features]") {
  light l;
  l.kind = light_kind::spot;
  l.position = {0.0f, 0.0f, 0.0f};
  l.direction = {0.0f, 0.0f, -1.0f};
  l.outer_angle = 10.0f;
  l.range = 10.0f;
  l.shadows = true;
  auto at = [](glm::vec3 p) { return object{shape_pane({1.0f, 1.0f}), glm::translate(glm::mat4(1.0f), p), 0}; };
  CHECK(light_reaches(l, at({0.0f, 0.0f, -5.0f})));   // on the axis
  CHECK(light_reaches(l, at({1.2f, 0.0f, -5.0f})));   // beside it, its sphere inside the cone
  CHECK_FALSE(light_reaches(l, at({3.0f, 0.0f, -5.0f})));
  CHECK_FALSE(light_reaches(l, at({0.0f, 0.0f, 5.0f})));   // behind
  CHECK_FALSE(light_reaches(l, at({0.0f, 0.0f, -12.0f})));  // past the range
  CHECK(light_reaches(l, at({0.0f, 0.0f, 0.2f})));    // around the light
  scene s;
  s.materials = {material{}, material{glm::vec3(1.0f), 0.5f}};
  s.objects = {at({0.0f, 0.0f, -5.0f})};
  CHECK_FALSE(sees_transparency(s, l));  // opaque
  s.objects[0].material = 1;
  CHECK(sees_transparency(s, l));
  l.shadows = false;
  CHECK_FALSE(sees_transparency(s, l));
}

TEST_CASE("add_file resolves #ifdef DST_ switches, keeps other directives, and maps lines", "[pipeline][glsl]") {
  const std::string path = "pipeline_test_switches.glsl";
  std::ofstream(path) << "float a;\n"                  // 1
                         "#ifdef DST_ONE\n"            // 2
                         "float one;\n"                // 3
                         "#ifndef DST_TWO\n"           // 4
                         "float one_not_two;\n"        // 5
                         "#else\n"                     // 6
                         "float one_and_two;\n"        // 7
                         "#endif\n"                    // 8
                         "#else\n"                     // 9
                         "float not_one;\n"            // 10
                         "#endif\n"                    // 11
                         "#ifdef VULKAN\n"             // 12
                         "#ifdef DST_TWO\n"            // 13
                         "float two;\n"                // 14
                         "#endif\n"                    // 15
                         "#endif\n";                   // 16
  auto text = [&](const std::vector<std::string>& on) {
    glsl::source src;
    REQUIRE(src.add_file(path, on));
    return src;
  };
  const glsl::source none = text({}), one = text({"DST_ONE"}), both = text({"DST_ONE", "DST_TWO"});
  CHECK(none.str() == "#version 450\nfloat a;\nfloat not_one;\n#ifdef VULKAN\n#endif\n");
  CHECK(one.str() == "#version 450\nfloat a;\nfloat one;\nfloat one_not_two;\n#ifdef VULKAN\n#endif\n");
  CHECK(both.str() == "#version 450\nfloat a;\nfloat one;\nfloat one_and_two;\n#ifdef VULKAN\nfloat two;\n#endif\n");
  CHECK(both.origin_of(4).line == 7);
  CHECK(both.origin_of(6).line == 14);
  std::ofstream(path) << "#if defined(DST_ONE)\n#endif\n";
  glsl::source bad;
  const auto r = bad.add_file(path, {});
  REQUIRE_FALSE(r);
  CHECK(r.error() == path + ":1: test dstrans switches with #ifdef or #ifndef");
  std::remove(path.c_str());
}

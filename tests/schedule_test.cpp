// The frame's schedule (dstrans/frame/schedule.hpp, render::schedule_of): passes in order, each read after
// its write, and no pass for an effect the frame does not draw.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>

#include <dstrans/frame/plan.hpp>
#include <scene_json.hpp>

using namespace dstrans;

namespace {

std::size_t count(const frame_schedule& s, const std::string& timer) {
  return std::size_t(std::count_if(s.passes.begin(), s.passes.end(), [&](const scheduled_pass& p) { return p.timer == timer; }));
}

scene example(const std::string& file) {
  auto s = load_scene(std::string(DSTRANS_SOURCE_DIR) + "/examples/scenes/" + file);
  INFO(s.error());
  REQUIRE(s);
  return *s;
}

}  // namespace

TEST_CASE("check_schedule finds a read before its write and a write nothing reads", "[schedule]") {
  frame_schedule s;
  s.passes.push_back({"gbuffer", "gbuffer pass", pass_kind::geometry, -1, {"scene"}, {"gbuffer"}});
  s.passes.push_back({"compose", "compose pass", pass_kind::fullscreen, -1, {"gbuffer"}, {"frame"}});
  CHECK(check_schedule(s, {"scene"}, {"frame"}));
  CHECK(check_schedule(s, {}, {"frame"}).error() == "gbuffer pass reads scene, which no pass before it writes");
  CHECK(check_schedule(s, {"scene"}, {}).error() == "compose pass writes frame, which nothing reads");
  std::swap(s.passes[0], s.passes[1]);
  CHECK(check_schedule(s, {"scene"}, {"frame"}).error() == "compose pass reads gbuffer, which no pass before it writes");
  CHECK(std::string(pass_kind_name(pass_kind::light_volume)) == "light volume");
}

TEST_CASE("every example scene's schedule reads what it wrote before, under every technique and setting", "[schedule]") {
  for (const auto& entry : std::filesystem::directory_iterator(std::string(DSTRANS_SOURCE_DIR) + "/examples/scenes")) {
    if (entry.path().extension() != ".json") continue;
    const scene s = example(entry.path().filename().string());
    for (render::technique t : {render::technique::interlaced, render::technique::peeling, render::technique::forward,
                                render::technique::forward_depth})
      for (render::shadow_mode m : render::all_lookups)
        for (auto particles : {render::options::particle_light::six_axes, render::options::particle_light::forward}) {
          render::options o;
          o.method = t;
          o.shadows = m;
          o.particles = particles;
          const render::frame_plan p = render::plan_of(s, o);
          const frame_schedule sched = render::schedule_of(s, p, o);
          INFO(entry.path().filename().string() << ", " << render::technique_name(t) << ", shadows "
                                                << render::shadow_name(m) << ", particles " << int(particles));
          const auto ok = check_schedule(sched, {"scene"}, {p.post.output});
          INFO(ok.error());
          CHECK(ok);
          std::size_t shadowed = 0;
          for (render::shadow_mode lookup : p.lookups) shadowed += lookup != render::shadow_mode::off;
          CHECK(count(sched, "shadow") == shadowed);
          CHECK(count(sched, "light") == s.lights.size() * std::size_t(p.forward ? 1 : p.layers));
          CHECK(count(sched, "gbuffer") == std::size_t(p.layers));
          for (const scheduled_pass& pass : sched.passes)
            if (pass.timer == "shadow" || pass.timer == "light") CHECK((pass.light >= 0 && pass.light < int(s.lights.size())));
        }
  }
}

TEST_CASE("a schedule has no pass for an effect the frame does not draw", "[schedule]") {
  render::options o;
  const scene pane = example("pane.json"), hair = example("hair.json"), smoke = example("smoke.json");
  const frame_schedule glass = render::schedule_of(pane, render::plan_of(pane, o), o);
  for (const char* absent : {"capture", "resolve", "particles", "bake", "ambient", "blend"}) {
    INFO(absent);
    CHECK(count(glass, absent) == 0);
  }
  const frame_schedule strands = render::schedule_of(hair, render::plan_of(hair, o), o);
  CHECK(count(strands, "capture") == 1);
  CHECK(count(strands, "resolve") == 1);
  const frame_schedule baked = render::schedule_of(smoke, render::plan_of(smoke, o), o);
  CHECK(count(baked, "particles") == 1);
  CHECK(count(baked, "bake") >= 2);  // the lights, and the texels into the atlas
  o.method = render::technique::forward;
  const frame_schedule forward = render::schedule_of(smoke, render::plan_of(smoke, o), o);
  CHECK(count(forward, "particles") == 0);  // forward rendering draws no particle systems
  CHECK(count(forward, "compose") == 0);
  CHECK(count(forward, "blend") == 1);
}

TEST_CASE("a schedule states each pass's fixed-function state, clears and geometry", "[schedule]") {
  for (const char* file : {"glass_room.json", "hair.json", "smoke.json", "glass_room_17.json"}) {
    const scene s = example(file);
    for (render::technique t : {render::technique::interlaced, render::technique::peeling, render::technique::forward}) {
      render::options o;
      o.method = t;
      const render::frame_plan p = render::plan_of(s, o);
      const frame_schedule sched = render::schedule_of(s, p, o);
      INFO(file << ", " << render::technique_name(t));
      for (const scheduled_pass& pass : sched.passes) {
        INFO(pass.label);
        const bool fills = pass.step == pass_step::gbuffer || pass.step == pass_step::ambient || pass.step == pass_step::shadow;
        CHECK((pass.state.depth == depth_test::less && pass.state.depth_write) == fills);
        CHECK(pass.clear_depth == fills);
        CHECK((pass.draws != geometry_set::none) == (pass.kind == pass_kind::geometry && pass.step != pass_step::particles));
        if (pass.step == pass_step::gbuffer) CHECK(pass.clears == render::gbuffer_clears(o.layout));
        if (pass.step == pass_step::shadow) CHECK(pass.draws == geometry_set::everything);
        if (pass.step == pass_step::capture) CHECK(pass.draws == geometry_set::hair);
        if (pass.step == pass_step::gbuffer || pass.step == pass_step::ambient || pass.step == pass_step::forward_light)
          CHECK(pass.draws == geometry_set::surfaces);
        if (pass.step == pass_step::light || pass.step == pass_step::forward_light) CHECK(pass.state.blend == blending::add);
        if (pass.step == pass_step::resolve || pass.step == pass_step::particles) CHECK(pass.state.blend == blending::over);
        // A light volume's back faces, depth clamped; a full-screen light neither.
        CHECK((pass.state.cull == culling::front) == (pass.kind == pass_kind::light_volume));
        CHECK(pass.state.depth_clamp == (pass.kind == pass_kind::light_volume));
        if (pass.step == pass_step::compose || pass.step == pass_step::blend || pass.step == pass_step::post)
          CHECK((pass.state.blend == blending::off && pass.state.depth == depth_test::off));
      }
      std::vector<std::string> cleared{"light buffer", "light buffer 2"};
      cleared.resize(std::size_t(p.layers));
      if (render::particle_plan_of(s, p, o).baking) cleared.push_back("volume atlas");
      CHECK(sched.cleared == cleared);
    }
  }
}

TEST_CASE("drawn_indices picks a pass's run of a flattened scene, and times_of sums a frame's passes by timer", "[schedule]") {
  CHECK(drawn_indices(geometry_set::surfaces, 30, 50).first == 0);
  CHECK(drawn_indices(geometry_set::surfaces, 30, 50).count == 30);
  CHECK(drawn_indices(geometry_set::hair, 30, 50).first == 30);
  CHECK(drawn_indices(geometry_set::hair, 30, 50).count == 20);
  CHECK(drawn_indices(geometry_set::everything, 30, 50).count == 50);
  CHECK(drawn_indices(geometry_set::none, 30, 50).count == 0);
  CHECK(drawn_indices(geometry_set::hair, 50, 50).count == 0);  // no hair
  frame_schedule s;
  s.passes = {scheduled_pass("shadow", "shadow pass, light 0", pass_kind::geometry, 0, {"scene"}, {"shadow map"}),
              scheduled_pass("light", "light pass, light 0", pass_kind::fullscreen, 0, {"shadow map"}, {"light buffer"}),
              scheduled_pass("shadow", "shadow pass, light 1", pass_kind::geometry, 1, {"scene"}, {"shadow map"})};
  const frame_times t = times_of(s, {1.0, 2.0, 4.0}, 9.0);
  CHECK(t.schedule == std::vector<std::string>{"shadow", "light", "shadow"});
  CHECK(t.pass_ms.at("shadow") == 5.0);
  CHECK(t.pass_ms.at("light") == 2.0);
  CHECK(t.frame_ms == 9.0);
}

// The frame's schedule (dstrans/frame/schedule.hpp, render::schedule_of): passes in order, each read after
// its write, and no pass for an effect the frame does not draw.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>

#include <dstrans/frame/culling.hpp>
#include <dstrans/frame/passes.hpp>
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

// A point light in glass_room's middle that casts shadows.
light shadowed_point_light() {
  light point;
  point.kind = light_kind::point;
  point.position = {0.3f, 1.7f, -0.2f};
  point.range = 8.0f;
  point.shadows = true;
  return point;
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
                                render::technique::forward_depth, render::technique::reference})
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
          std::size_t shadow_views = 0;  // a pass for each view of each shadowed light's map
          const std::vector<render::light_block> blocks = render::light_blocks(s);
          for (std::size_t i = 0; i < p.lookups.size(); ++i)
            if (p.lookups[i] != render::shadow_mode::off) shadow_views += std::size_t(render::shadow_views(blocks[i]));
          CHECK(count(sched, "shadow") == shadow_views);
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

TEST_CASE("schedule_of and particle_plan_of from the scene's light blocks equal the plain ones; a light's lookup is "
          "transparent where it sees glass", "[schedule]") {
  auto same_passes = [](const frame_schedule& a, const frame_schedule& b) {
    REQUIRE(a.passes.size() == b.passes.size());
    CHECK(a.cleared == b.cleared);
    for (std::size_t k = 0; k < a.passes.size(); ++k) {
      INFO(a.passes[k].label);
      CHECK(a.passes[k].label == b.passes[k].label);
      CHECK((a.passes[k].light == b.passes[k].light && a.passes[k].index == b.passes[k].index));
      CHECK(a.passes[k].draws == b.passes[k].draws);
      CHECK(a.passes[k].view_proj == b.passes[k].view_proj);
    }
  };
  auto same_lights = [](const std::vector<volume_light>& a, const std::vector<volume_light>& b) {
    REQUIRE(a.size() == b.size());
    for (std::size_t k = 0; k < a.size(); ++k)
      CHECK((a[k].position_kind == b[k].position_kind && a[k].direction_range == b[k].direction_range &&
             a[k].colour_cos_outer == b[k].colour_cos_outer && a[k].cos_inner == b[k].cos_inner));
  };
  render::options o;
  o.shadows = render::shadow_mode::transparent;
  o.opaque_shadows_depth_only = true;
  for (const char* file : {"glass_room_smoke.json", "glass_room_lamp.json", "smoke.json", "hair.json"}) {
    INFO(file);
    const scene s = example(file);
    const render::frame_plan p = render::plan_of(s, o);
    REQUIRE(p.lookups.size() == s.lights.size());
    for (std::size_t i = 0; i < s.lights.size(); ++i)
      CHECK(p.lookups[i] == (!casts_shadows(s.lights[i]) || p.shadows == render::shadow_mode::off            ? render::shadow_mode::off
                             : p.shadows == render::shadow_mode::transparent && sees_transparency(s, s.lights[i]) ? render::shadow_mode::transparent
                                                                                                               : render::shadow_mode::opaque));
    const std::vector<render::light_block> lights = render::light_blocks(s);
    const frame_schedule plain = render::schedule_of(s, p, o);
    CHECK(plain.passes.size() > 2);
    same_passes(plain, render::schedule_of(s, p, o, lights));
    same_passes(plain, render::schedule_of(s, p, o, {}));  // of another length: computed again
    const render::particle_plan smoke = render::particle_plan_of(s, p, o);
    for (const render::particle_plan& other : {render::particle_plan_of(s, p, o, lights), render::particle_plan_of(s, p, o, {})}) {
      CHECK((other.on == smoke.on && other.baking == smoke.baking && other.shadows == smoke.shadows));
      CHECK(other.ranges == smoke.ranges);
      same_lights(other.shadowed_lights, smoke.shadowed_lights);
      same_lights(other.unshadowed_lights, smoke.unshadowed_lights);
    }
  }
}

TEST_CASE("the exact reference: opaque surfaces deferred, every transparent fragment into the lists, no refraction", "[schedule][exact]") {
  render::options o;
  o.method = render::technique::reference;
  for (const char* file : {"hair_panes.json", "glass_room_smoke.json", "pane.json", "smoke.json"}) {
    INFO(file);
    const scene s = example(file);
    const render::frame_plan p = render::plan_of(s, o);
    CHECK(p.exact);
    CHECK(p.lists);
    CHECK_FALSE(p.around_glass);
    CHECK_FALSE(p.on.has(effect::refraction));
    CHECK(p.layers == 1);
    const frame_schedule sched = render::schedule_of(s, p, o);
    CHECK(count(sched, "capture") == 1);
    CHECK(count(sched, "resolve") == 1);
    CHECK(count(sched, "particles") == (s.particles.empty() ? 0u : 1u));
    CHECK(count(sched, "bake") == 0);  // its particles are lit per fragment
    int capture = -1, compose = -1, resolve = -1;
    for (std::size_t k = 0; k < sched.passes.size(); ++k) {
      const scheduled_pass& pass = sched.passes[k];
      if (pass.timer == "capture") capture = int(k);
      if (pass.timer == "compose") compose = int(k);
      if (pass.timer == "resolve") resolve = int(k);
      if (pass.timer == "capture") CHECK(pass.draws == geometry_set::everything);  // glass and hair alike
      if (pass.timer == "particles") CHECK(pass.writes == std::vector<std::string>{"kbuffer"});
    }
    CHECK((compose < capture && capture < resolve));  // over the composed opaque frame
    CHECK(sched.passes[std::size_t(resolve)].state.blend == blending::over);
    // Every shadowed light's map is copied into its layer, which the capture reads.
    const bool shadowed = p.uses(render::shadow_mode::opaque) || p.uses(render::shadow_mode::transparent);
    CHECK(p.shadow_layers == shadowed);
    CHECK(count(sched, "shadow layers") == (shadowed ? render::particle_plan_of(s, p, o).shadowed_lights.size() : 0u));
  }
  // A scene with nothing transparent is plain deferred shading: no lists.
  scene opaque = example("pane.json");
  for (material& m : opaque.materials) m.alpha = 1.0f;
  const render::frame_plan plain = render::plan_of(opaque, o);
  CHECK_FALSE(plain.lists);
  CHECK(count(render::schedule_of(opaque, plain, o), "capture") == 0);
}

TEST_CASE("hair and particles are drawn around the glass only in a deferred frame that has glass", "[schedule][glass_layers]") {
  const scene hair = example("hair.json"), smoke = example("smoke.json"), hair_and_panes = example("hair_panes.json");
  auto index_of = [](const frame_schedule& s, const std::string& timer) {
    for (std::size_t i = 0; i < s.passes.size(); ++i)
      if (s.passes[i].timer == timer) return int(i);
    return -1;
  };
  for (render::technique t : {render::technique::interlaced, render::technique::peeling, render::technique::forward}) {
    render::options o;
    o.method = t;
    INFO(render::technique_name(t));
    // Hair alone: over the composed frame, nothing more made.
    const render::frame_plan alone = render::plan_of(hair, o);
    CHECK_FALSE(alone.around_glass);
    CHECK(alone.pipeline.target("glass.behind") == nullptr);
    for (const scheduled_pass& p : render::schedule_of(hair, alone, o).passes)
      CHECK(std::find(p.writes.begin(), p.writes.end(), "glass layers") == p.writes.end());
    const scene* around[] = {&hair_and_panes, &smoke};
    for (const scene* s : around) {
      const render::frame_plan p = render::plan_of(*s, o);
      CHECK(p.around_glass == (t != render::technique::forward));
      if (!p.around_glass) continue;
      const frame_schedule sched = render::schedule_of(*s, p, o);
      const int compose = index_of(sched, "compose"), layered = index_of(sched, s == &smoke ? "particles" : "resolve");
      REQUIRE(compose >= 0);
      REQUIRE(layered >= 0);
      // Drawn before the compose into the glass layers, which the first such pass clears to nothing drawn.
      CHECK(layered < compose);
      CHECK(sched.passes[std::size_t(layered)].writes == std::vector<std::string>{"glass layers"});
      CHECK(sched.passes[std::size_t(layered)].clears == std::vector<glm::vec4>(2, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)));
      const std::vector<std::string>& reads = sched.passes[std::size_t(compose)].reads;
      CHECK(std::find(reads.begin(), reads.end(), "glass layers") != reads.end());
      // Two RGBA16F targets, as the renderers make them, counted in the frame's bytes a pixel.
      const std::vector<target_desc> made = glass_layer_targets();
      REQUIRE(made.size() == 2);
      for (const char* name : {"glass.behind", "glass.front"}) {
        const planned_target* target = p.pipeline.target(name);
        REQUIRE(target);
        CHECK(target->bytes_per_pixel == info(made[target->name == "glass.front" ? 1 : 0].fmt).bytes_per_pixel);
        CHECK(target->format == info(format::rgba16f).name);
      }
    }
  }
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
        // A cube's later faces draw into the map its first face cleared.
        CHECK(pass.clear_depth == (fills && !(pass.step == pass_step::shadow && pass.index > 0)));
        CHECK((pass.draws != geometry_set::none) == (pass.kind == pass_kind::geometry && pass.step != pass_step::particles));
        if (pass.step == pass_step::gbuffer) CHECK(pass.clears == render::gbuffer_clears(o.layout));
        if (pass.step == pass_step::shadow) CHECK(pass.draws == geometry_set::everything);
        if (pass.step == pass_step::capture) CHECK(pass.draws == geometry_set::hair);
        if (pass.step == pass_step::gbuffer || pass.step == pass_step::ambient || pass.step == pass_step::forward_light)
          CHECK(pass.draws == geometry_set::surfaces);
        if (pass.step == pass_step::light || pass.step == pass_step::forward_light) CHECK(pass.state.blend == blending::add);
        // Over the frame, or around the glass into layers that keep what they let through.
        if (pass.step == pass_step::resolve || pass.step == pass_step::particles)
          CHECK(pass.state.blend == (p.around_glass ? blending::layer : blending::over));
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

// The cube's six faces are drawn into disjoint tiles of the one map, each from the view that the lookups
// (dst_map_view_point, dst_map_texel) take a point in that face's direction to: the pass's clip position
// is the lookup's, and its texel lies in the pass's tile.
TEST_CASE("a point light's shadow map is six faces drawn into the tiles of one map, where the lookups find them", "[schedule][shadow]") {
  scene s = example("glass_room.json");
  const light point = shadowed_point_light();
  s.lights = {point};
  render::options o;
  o.shadow_size = 100;
  const render::frame_plan p = render::plan_of(s, o);
  const frame_schedule sched = render::schedule_of(s, p, o);
  std::vector<scheduled_pass> faces;
  for (const scheduled_pass& pass : sched.passes)
    if (pass.step == pass_step::shadow) faces.push_back(pass);
  REQUIRE(faces.size() == 6);
  const render::light_block lb = render::light_blocks(s)[0];
  CHECK(render::shadow_views(lb) == 6);
  const glm::ivec2 size(o.shadow_size);
  for (int v = 0; v < 6; ++v) {
    const scheduled_pass& f = faces[std::size_t(v)];
    INFO("face " << v);
    CHECK(f.index == v);
    CHECK(f.light == 0);
    CHECK(f.clear_depth == (v == 0));
    CHECK(f.clears.empty() == (v > 0));
    CHECK(f.area == glm::ivec4(v % 3 * 32, v / 3 * 32, 32, 32));  // 100 / 3 = 33, even: 32
    const render::frame_block view = render::light_frame(s, lb, o, v);
    std::mt19937 rng{unsigned(v)};
    std::uniform_real_distribution<float> across(-0.99f, 0.99f), along(0.2f, 3.0f);
    for (int k = 0; k < 50; ++k) {
      // A point in face v's direction: its axis component the largest.
      glm::vec3 d(across(rng), across(rng), across(rng));
      d[v / 2] = (v % 2 ? -1.0f : 1.0f);
      d *= along(rng);
      const glm::vec3 world = point.position + d;
      REQUIRE(shader::dst_cube_face(d) == v);
      const glm::vec4 drawn = view.view_proj * glm::vec4(world, 1.0f);
      const glm::vec4 looked = lb.shadow_view_proj * glm::vec4(shader::dst_map_view_point(world, point.position, lb.cos_inner), 1.0f);
      for (int c = 0; c < 4; ++c) CHECK(drawn[c] == Approx(looked[c]).margin(1e-5));
      CHECK(std::abs(drawn.x) <= drawn.w);
      CHECK(std::abs(drawn.y) <= drawn.w);
      const glm::ivec2 origin = shader::dst_map_tile_origin(world, point.position, lb.cos_inner, size);
      const glm::ivec2 extent = shader::dst_map_tile_extent(lb.cos_inner, size);
      CHECK(origin == glm::ivec2(f.area));
      CHECK(extent == glm::ivec2(f.area.z, f.area.w));
      const glm::ivec2 texel = shader::dst_map_texel(glm::vec2(looked) / looked.w, origin, extent, lb.cos_inner);
      CHECK(shader::dst_tile_holds(texel, origin, extent));
    }
  }
  // Spot and directional maps are drawn once, into the whole map.
  s.lights[0].kind = light_kind::spot;
  const frame_schedule spot = render::schedule_of(s, render::plan_of(s, o), o);
  CHECK(count(spot, "shadow") == 1);
  for (const scheduled_pass& pass : spot.passes)
    if (pass.step == pass_step::shadow) CHECK(pass.area == glm::ivec4(0));
  CHECK(render::shadow_views(render::light_blocks(s)[0]) == 1);
}

TEST_CASE("drawn_indices picks a pass's run of a flattened scene, and times_of sums a frame's passes by timer", "[schedule]") {
  CHECK(drawn_indices(geometry_set::surfaces, 30, 50).first == 0);
  CHECK(drawn_indices(geometry_set::surfaces, 30, 50).count == 30);
  CHECK(drawn_indices(geometry_set::hair, 30, 50).first == 30);
  CHECK(drawn_indices(geometry_set::hair, 30, 50).count == 20);
  CHECK(drawn_indices(geometry_set::everything, 30, 50).count == 50);
  CHECK(drawn_indices(geometry_set::none, 30, 50).count == 0);
  CHECK(drawn_indices(geometry_set::hair, 50, 50).count == 0);  // no hair
  // Not knowing which objects are opaque: the depth-only pass draws nothing, the rest everything.
  CHECK(drawn_indices(geometry_set::opaque, 30, 50).count == 0);
  CHECK(drawn_indices(geometry_set::not_opaque, 30, 50).first == 0);
  CHECK(drawn_indices(geometry_set::not_opaque, 30, 50).count == 50);
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

TEST_CASE("outside_clip culls a sphere wholly beyond a plane of the clip volume, and nothing it cannot place", "[schedule][culling]") {
  // A camera at the origin looking down -Z, 90 degrees, depth from 1 to 10: at z = -5 the sides are at +-5.
  const glm::mat4 m = glm::perspectiveRH_ZO(glm::radians(90.0f), 1.0f, 1.0f, 10.0f);
  CHECK_FALSE(outside_clip(m, {0, 0, -5}, 0.5f, false));
  CHECK_FALSE(outside_clip(m, {5.5f, 0, -5}, 1.0f, false));  // across the right plane
  CHECK(outside_clip(m, {20, 0, -5}, 1.0f, false));
  CHECK(outside_clip(m, {0, -7, -5}, 1.0f, false));
  CHECK(outside_clip(m, {0, 0, 5}, 1.0f, false));   // behind the camera
  CHECK(outside_clip(m, {0, 0, -20}, 1.0f, false));  // beyond the far plane...
  CHECK_FALSE(outside_clip(m, {0, 0, -20}, 1.0f, true));  // ...which depth clamping draws
  CHECK_FALSE(outside_clip(m, {0, 0, -10.5f}, 1.0f, false));  // across it
  CHECK(outside_clip(m, {0, 0, -0.2f}, 0.1f, false));  // before OpenGL's near plane, so before Vulkan's
  const float nan = std::numeric_limits<float>::quiet_NaN();
  CHECK_FALSE(outside_clip(glm::mat4(0.0f), {20, 0, -5}, 1.0f, false));  // unknown: drawn
  CHECK_FALSE(outside_clip(m, {nan, 0, -5}, 1.0f, false));
  CHECK_FALSE(outside_clip(m, {20, 0, -5}, nan, false));
}

TEST_CASE("visible_runs draws a pass's run less the parts outside its clip volume, neighbours as one run", "[schedule][culling]") {
  const glm::mat4 m = glm::perspectiveRH_ZO(glm::radians(90.0f), 1.0f, 1.0f, 10.0f);
  const glm::vec3 in(0, 0, -5), out(20, 0, -5);
  std::vector<mesh_part> parts = {{0, 6, in, 1.0f}, {6, 6, in, 1.0f}, {12, 6, out, 1.0f}, {18, 6, in, 1.0f}, {24, 6, in, 1.0f}};
  scheduled_pass pass;
  pass.draws = geometry_set::everything;
  pass.view_proj = m;
  auto runs = visible_runs(parts, 24, 30, pass);
  REQUIRE(runs.size() == 2);
  CHECK((runs[0].first == 0 && runs[0].count == 12));
  CHECK((runs[1].first == 18 && runs[1].count == 12));
  pass.draws = geometry_set::surfaces;  // the hair, from 24, is not the pass's
  runs = visible_runs(parts, 24, 30, pass);
  REQUIRE(runs.size() == 2);
  CHECK((runs[1].first == 18 && runs[1].count == 6));
  pass.draws = geometry_set::hair;
  runs = visible_runs(parts, 24, 30, pass);
  REQUIRE(runs.size() == 1);
  CHECK((runs[0].first == 24 && runs[0].count == 6));
  parts[4].centre = out;
  CHECK(visible_runs(parts, 24, 30, pass).empty());
  pass.view_proj = glm::mat4(0.0f);  // unknown: all of it
  runs = visible_runs(parts, 24, 30, pass);
  REQUIRE(runs.size() == 1);
  CHECK(runs[0].count == 6);
  pass.draws = geometry_set::everything;
  runs = visible_runs({}, 24, 30, pass);  // no parts: drawn_indices' run
  REQUIRE(runs.size() == 1);
  CHECK(runs[0].count == 30);
  pass.draws = geometry_set::none;
  CHECK(visible_runs(parts, 24, 30, pass).empty());
}

TEST_CASE("visible_runs splits a pass's parts by mesh_part::opaque for the two passes of a transparent shadow map", "[schedule][culling]") {
  const glm::mat4 m = glm::perspectiveRH_ZO(glm::radians(90.0f), 1.0f, 1.0f, 10.0f);
  const glm::vec3 in(0, 0, -5), out(20, 0, -5);
  // Opaque, opaque, glass, opaque outside the view, glass, hair (from 30).
  const std::vector<mesh_part> parts = {{0, 6, in, 1.0f, true},    {6, 6, in, 1.0f, true},  {12, 6, in, 1.0f, false},
                                        {18, 6, out, 1.0f, true},  {24, 6, in, 1.0f, false}, {30, 6, in, 1.0f, false}};
  scheduled_pass pass;
  pass.view_proj = m;
  pass.draws = geometry_set::opaque;
  auto runs = visible_runs(parts, 30, 36, pass);
  REQUIRE(runs.size() == 1);
  CHECK((runs[0].first == 0 && runs[0].count == 12));
  pass.draws = geometry_set::not_opaque;  // the glass and the hair
  runs = visible_runs(parts, 30, 36, pass);
  REQUIRE(runs.size() == 2);
  CHECK((runs[0].first == 12 && runs[0].count == 6));
  CHECK((runs[1].first == 24 && runs[1].count == 12));
  // Without parts, drawn_indices' runs: nothing depth only, everything with the full shader.
  CHECK(visible_runs({}, 30, 36, pass).front().count == 36);
  pass.draws = geometry_set::opaque;
  CHECK(visible_runs({}, 30, 36, pass).empty());
}

TEST_CASE("culls_back_faces: a pass that keeps the nearest surface culls a closed part wholly beyond its near plane", "[schedule][culling]") {
  scheduled_pass pass;
  pass.state.cull_closed = true;
  mesh_part part{0, 6, {0, 0, -5}, 1.0f, true, true};
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // OpenGL's and Vulkan's depth ranges: near plane 1, far 10.
  for (const glm::mat4& m : {glm::perspective(glm::radians(90.0f), 1.0f, 1.0f, 10.0f), glm::perspectiveRH_ZO(glm::radians(90.0f), 1.0f, 1.0f, 10.0f)}) {
    pass.view_proj = m;
    part.centre = {0, 0, -5};
    CHECK(culls_back_faces(pass, part));
    part.centre = {0, 0, -1.5f};  // across the near plane: clipping opens it
    CHECK_FALSE(culls_back_faces(pass, part));
    part.centre = {0, 0, 0};  // around the viewpoint
    CHECK_FALSE(culls_back_faces(pass, part));
    part.centre = {nan, 0, -5};
    CHECK_FALSE(culls_back_faces(pass, part));
  }
  // Beyond the near plane by a hair more than the radius: Vulkan's depth range (dstrans's on both APIs)
  // clips there; OpenGL's default one's 0 <= z lies farther out, so such a matrix culls a little less.
  part.centre = {0, 0, -2.1f};
  CHECK(culls_back_faces(pass, part));
  pass.view_proj = glm::perspective(glm::radians(90.0f), 1.0f, 1.0f, 10.0f);
  CHECK_FALSE(culls_back_faces(pass, part));
  part.centre = {0, 0, -5};
  part.closed = false;
  CHECK_FALSE(culls_back_faces(pass, part));
  part.closed = true;
  pass.state.cull_closed = false;  // a pass that keeps more than the nearest surface
  CHECK_FALSE(culls_back_faces(pass, part));
  pass.state.cull_closed = true;
  pass.view_proj = glm::mat4(0.0f);  // unknown
  CHECK_FALSE(culls_back_faces(pass, part));
  // An orthographic view (a directional light's) has no viewpoint: only its near plane counts.
  pass.view_proj = glm::orthoRH_ZO(-10.0f, 10.0f, -10.0f, 10.0f, 1.0f, 20.0f);
  CHECK(culls_back_faces(pass, part));
  part.centre = {0, 0, -1.5f};
  CHECK_FALSE(culls_back_faces(pass, part));
}

TEST_CASE("visible_runs joins neighbouring parts only where both may cull their back faces or neither", "[schedule][culling]") {
  const glm::vec3 in(0, 0, -5);
  // Closed, closed, open, closed, closed (hair from 30).
  const std::vector<mesh_part> parts = {{0, 6, in, 1.0f, true, true},   {6, 6, in, 1.0f, true, true}, {12, 6, in, 1.0f, true, false},
                                        {18, 6, in, 1.0f, false, true}, {24, 6, in, 1.0f, false, true}};
  scheduled_pass pass;
  pass.view_proj = glm::perspective(glm::radians(90.0f), 1.0f, 1.0f, 10.0f);
  pass.draws = geometry_set::everything;
  pass.state.cull_closed = true;
  auto runs = visible_runs(parts, 30, 30, pass);
  REQUIRE(runs.size() == 3);
  CHECK((runs[0].first == 0 && runs[0].count == 12 && runs[0].cull_back));
  CHECK((runs[1].first == 12 && runs[1].count == 6 && !runs[1].cull_back));
  CHECK((runs[2].first == 18 && runs[2].count == 12 && runs[2].cull_back));
  pass.state.cull_closed = false;
  runs = visible_runs(parts, 30, 30, pass);
  REQUIRE(runs.size() == 1);
  CHECK((runs[0].count == 30 && !runs[0].cull_back));
  CHECK_FALSE(visible_runs({}, 30, 30, pass).front().cull_back);  // without parts nothing is known closed
}

TEST_CASE("the shadow passes, and only they, may cull closed objects, of which glass_room's spheres and bottles are", "[schedule][culling]") {
  const scene s = example("glass_room.json");
  const scene_mesh m = flatten(s);
  std::size_t closed = 0;
  for (const mesh_part& part : m.parts) closed += part.closed;
  CHECK(closed > m.parts.size() / 2);
  render::options o;
  o.opaque_shadows_depth_only = true;
  const frame_schedule sched = render::schedule_of(s, render::plan_of(s, o), o);
  std::size_t culled = 0;
  for (const scheduled_pass& pass : sched.passes) {
    INFO(pass.label);
    CHECK(pass.state.cull_closed == (pass.step == pass_step::shadow));
    for (const index_run& run : visible_runs(m.parts, m.hair_first, m.indices.size(), pass)) culled += run.cull_back ? run.count : 0;
  }
  CHECK(culled > 0);
}

TEST_CASE("draws tells an engine's callback, for every set, the objects visible_runs draws of dstrans's own mesh", "[schedule][culling]") {
  material opaque, glass, cut, hair, unknown;
  glass.alpha = 0.4f;
  cut.alpha_cutoff = 0.5f;  // alpha-tested: its dropped fragments cast no shadow
  hair.hair = true;
  unknown.alpha = NAN;
  const std::vector<material> materials = {opaque, glass, cut, unknown, hair};  // hair last, as flatten puts it
  std::vector<mesh_part> parts;
  for (std::size_t k = 0; k < materials.size(); ++k)
    parts.push_back({6 * k, 6, glm::vec3(0, 0, -5), 1.0f, materials[k].opaque()});
  scheduled_pass pass;
  pass.view_proj = glm::perspectiveRH_ZO(glm::radians(90.0f), 1.0f, 1.0f, 10.0f);
  for (geometry_set set : {geometry_set::none, geometry_set::surfaces, geometry_set::hair, geometry_set::everything,
                           geometry_set::opaque, geometry_set::not_opaque}) {
    pass.draws = set;
    const std::vector<index_run> runs = visible_runs(parts, 24, 30, pass);
    for (std::size_t k = 0; k < materials.size(); ++k) {
      bool drawn = false;
      for (const index_run& r : runs) drawn = drawn || (r.first <= 6 * k && 6 * k + 6 <= r.first + r.count);
      INFO("set " << int(set) << ", material " << k);
      CHECK(draws(set, materials[k]) == drawn);
    }
  }
  CHECK(draws(geometry_set::opaque, opaque));
  CHECK_FALSE(draws(geometry_set::opaque, cut));
  CHECK(draws(geometry_set::not_opaque, hair));
  CHECK_FALSE(draws(geometry_set::surfaces, hair));
  CHECK_FALSE(draws(geometry_set::none, opaque));
}

TEST_CASE("with opaque_shadows_depth_only each view of a transparent shadow map is a pass of its opaque surfaces, then the rest",
          "[schedule][shadow]") {
  scene s = example("glass_room.json");
  s.lights.push_back(shadowed_point_light());  // a cube of six views besides the spot lights
  render::options o;
  const frame_schedule single = render::schedule_of(s, render::plan_of(s, o), o);
  o.opaque_shadows_depth_only = true;
  const render::frame_plan p = render::plan_of(s, o);
  REQUIRE(p.shadows == render::shadow_mode::transparent);
  CHECK(p.depth_only_shadows);
  const frame_schedule split = render::schedule_of(s, p, o);
  std::vector<scheduled_pass> once, twice;
  for (const scheduled_pass& pass : single.passes)
    if (pass.step == pass_step::shadow) once.push_back(pass);
  for (const scheduled_pass& pass : split.passes)
    if (pass.step == pass_step::shadow) twice.push_back(pass);
  REQUIRE(twice.size() == 2 * once.size());
  CHECK(split.passes.size() == single.passes.size() + once.size());
  for (std::size_t k = 0; k < once.size(); ++k) {
    const scheduled_pass &a = twice[2 * k], &b = twice[2 * k + 1], &whole = once[k];
    INFO(whole.label);
    for (const scheduled_pass* half : {&a, &b}) {
      CHECK(half->light == whole.light);
      CHECK(half->index == whole.index);
      CHECK(half->area == whole.area);
      CHECK(half->view_proj == whole.view_proj);
      CHECK(half->state.depth == whole.state.depth);
      CHECK(half->state.depth_write == whole.state.depth_write);
      CHECK(half->state.blend == whole.state.blend);
    }
    CHECK(a.draws == geometry_set::opaque);
    CHECK(a.clears == whole.clears);  // the first half clears what the single pass cleared
    CHECK(a.clear_depth == whole.clear_depth);
    CHECK(b.draws == geometry_set::not_opaque);
    CHECK(b.clears.empty());
    CHECK_FALSE(b.clear_depth);
  }
  // A map of depth alone is drawn once a view, as before.
  o.shadows = render::shadow_mode::opaque;
  const render::frame_plan plain = render::plan_of(s, o);
  CHECK_FALSE(plain.depth_only_shadows);
  for (const scheduled_pass& pass : render::schedule_of(s, plain, o).passes)
    if (pass.step == pass_step::shadow) CHECK(pass.draws == geometry_set::everything);
}

TEST_CASE("a pass draws with its light view's matrix or the camera's, against which a point light's faces cull the scene",
          "[schedule][culling]") {
  const scene lamp = example("glass_room_lamp.json");
  render::options o;
  frame_schedule s = render::schedule_of(lamp, render::plan_of(lamp, o), o);
  const auto lights = render::light_blocks(lamp);
  const glm::mat4 camera = render::camera_frame(lamp, lamp.view, o).view_proj;
  set_camera_view(s, camera);
  const scene_mesh m = flatten(lamp);
  int faces = 0;
  for (const scheduled_pass& pass : s.passes) {
    if (pass.step != pass_step::shadow) {
      CHECK(pass.view_proj == camera);
      continue;
    }
    ++faces;
    CHECK(pass.view_proj == render::light_frame(lamp, lights[std::size_t(pass.light)], o, pass.index).view_proj);
    std::size_t drawn = 0;
    for (const index_run& run : visible_runs(m.parts, m.hair_first, m.indices.size(), pass)) drawn += run.count;
    INFO(pass.label);
    CHECK(drawn > 0);
    CHECK(drawn < m.indices.size());  // each face sees a part of the room
  }
  CHECK(faces == 6);
}

TEST_CASE("temporal interlacing: planned for glass on the interlaced technique, the previous frame kept and counted",
          "[schedule][temporal]") {
  render::options o;
  o.temporal = true;
  const scene room = example("glass_room.json");
  for (render::gbuffer_layout l : {render::gbuffer_layout::thesis, render::gbuffer_layout::compact}) {
    o.layout = l;
    const render::frame_plan p = render::plan_of(room, o);
    CHECK(p.temporal);
    CHECK(p.layers == 1);
    CHECK(p.kept_layers() == 2);
    // Table 3.1's 20 bytes or the compact 12, twice.
    CHECK(p.pipeline.bytes_per_pixel == (l == render::gbuffer_layout::thesis ? 40 : 24));
    CHECK(p.pipeline.target("previous.gbuffer.RT0"));
    CHECK(p.pipeline.target("previous.light.RT0"));
    CHECK(p.pipeline.pass("compose")->switches.back() == "DST_TEMPORAL");
    const frame_schedule sched = render::schedule_of(room, p, o);
    CHECK(count(sched, "gbuffer") == 1u);
    CHECK(check_schedule(sched, {"scene", "previous gbuffer", "previous light buffer"}, {p.post.output}));
    CHECK(!check_schedule(sched, {"scene"}, {p.post.output}));
    render::options one = o;
    one.temporal = false;
    CHECK(render::frame_bytes(p, o) == render::frame_bytes(render::plan_of(room, one), one) +
                                           std::size_t(p.pipeline.bytes_per_pixel / 2) * std::size_t(o.width) * std::size_t(o.height));
  }
  // Nothing to keep without glass, or where another technique draws the frame.
  o.layout = render::gbuffer_layout::thesis;
  const render::frame_plan none = render::plan_of(example("glass_room_0.json"), o);
  CHECK(!none.temporal);
  CHECK(none.kept_layers() == 1);
  CHECK(none.pipeline.bytes_per_pixel == 20);
  for (render::technique t : {render::technique::peeling, render::technique::forward, render::technique::forward_depth}) {
    o.method = t;
    CHECK(!render::plan_of(room, o).temporal);
  }
}

TEST_CASE("temporal interlacing alternates every predicate's phase and hands each frame the one before", "[schedule][temporal]") {
  const glm::ivec2 size(7, 5);
  for (render::predicate p : {render::predicate::rows, render::predicate::columns, render::predicate::checker}) {
    INFO(render::predicate_name(p));
    CHECK(render::interlace_phase(p, 0) == glm::ivec2(0));
    CHECK(render::interlace_phase(p, 2) == glm::ivec2(0));
    CHECK(render::interlace_phase(p, 1) == render::interlace_phase(p, 3));
    for (int y = 0; y < size.y; ++y)
      for (int x = 0; x < size.x; ++x) {
        const glm::ivec2 a = glm::ivec2(x, y) + render::interlace_phase(p, 0), b = glm::ivec2(x, y) + render::interlace_phase(p, 1);
        const bool flips = p == render::predicate::rows      ? interlace::rows::keep(a, size) != interlace::rows::keep(b, size)
                           : p == render::predicate::columns ? interlace::columns::keep(a, size) != interlace::columns::keep(b, size)
                                                             : interlace::checker::keep(a, size) != interlace::checker::keep(b, size);
        CHECK(flips);
      }
  }
  const scene room = example("glass_room.json");
  render::options o;
  o.temporal = true;
  const render::frame_plan p = render::plan_of(room, o);
  const render::frame_block first = render::sequence_frame(render::camera_frame(room, o), {}, 0, p, o);
  CHECK(first.interlace == glm::ivec4(0, 0, 0, 0));  // no previous frame
  CHECK(first.to_previous == glm::mat4(1.0f));
  CHECK(first.from_previous == glm::mat4(1.0f));
  const render::frame_block still = render::sequence_frame(render::camera_frame(room, o), first, 1, p, o);
  CHECK(still.interlace == glm::ivec4(0, 1, 1, 1));
  camera moved = room.view;
  moved.position.x += 0.1f;
  const render::frame_block next = render::sequence_frame(render::camera_frame(room, moved, o), still, 2, p, o);
  CHECK(next.interlace == glm::ivec4(0, 0, 1, 0));
  CHECK(next.view_proj != still.view_proj);
  // The compose pass's still-camera variant: only where a previous frame was seen from the same place.
  CHECK(render::still_camera(still));
  CHECK_FALSE(render::still_camera(first));
  CHECK_FALSE(render::still_camera(next));
  // A world point's clip position now, taken to the previous frame, is where that frame's camera saw it;
  // and back again.
  const glm::vec4 world(0.3f, 0.9f, -0.4f, 1.0f);
  const glm::vec4 now = next.view_proj * world, before = still.view_proj * world;
  const glm::vec4 to = next.to_previous * now, back = next.from_previous * before;
  for (int k = 0; k < 3; ++k) {
    CHECK(to[k] / to.w == Approx(before[k] / before.w).margin(1e-5));
    CHECK(back[k] / back.w == Approx(now[k] / now.w).margin(1e-5));
  }
  for (const render::frame_block* f : {&still, &first})
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) {
        CHECK(f->to_previous[c][r] == Approx(c == r ? 1.0f : 0.0f).margin(1e-6));
        CHECK(f->from_previous[c][r] == Approx(c == r ? 1.0f : 0.0f).margin(1e-6));
      }
  // Without temporal interlacing a frame is the camera's as it is.
  o.temporal = false;
  const render::frame_block plain = render::sequence_frame(render::camera_frame(room, moved, o), still, 2, render::plan_of(room, o), o);
  CHECK(plain.interlace == glm::ivec4(0));
  CHECK(plain.to_previous == glm::mat4(1.0f));
  CHECK_FALSE(render::still_camera(plain));
}

TEST_CASE("the frame block counts the scene's lights, which a shader loops over, none included", "[schedule]") {
  scene room = example("glass_room.json");
  const render::options o;
  CHECK(std::size_t(render::camera_frame(room, o).counts.x) == room.lights.size());
  CHECK(std::size_t(render::camera_frame(room, room.view, o).counts.x) == render::light_blocks(room).size());
  CHECK(render::light_frame(room, render::light_blocks(room).front(), o).counts.x == int(room.lights.size()));
  room.lights.clear();
  CHECK(render::camera_frame(room, room.view, o).counts == glm::ivec4(0));
}

TEST_CASE("the frame block names the light whose shadow map hair reads: the last shadowed one, none without", "[schedule]") {
  scene room = example("glass_room.json");
  REQUIRE(room.lights.size() >= 2);
  for (light& l : room.lights) l.shadows = true;
  room.lights.back().shadows = false;
  render::options o;
  for (bool temporal : {false, true}) {
    o.temporal = temporal;
    const render::frame_plan p = render::plan_of(room, o);
    CHECK(render::hair_shadow_light(p) == int(room.lights.size()) - 2);
    const render::frame_block first = render::sequence_frame(render::camera_frame(room, o), {}, 0, p, o);
    CHECK(first.params.z == float(room.lights.size() - 2));
    CHECK(render::sequence_frame(render::camera_frame(room, o), first, 1, p, o).params.z == first.params.z);
  }
  o.shadows = render::shadow_mode::off;
  const render::frame_plan dark = render::plan_of(room, o);
  CHECK(render::hair_shadow_light(dark) == -1);
  CHECK(render::sequence_frame(render::camera_frame(room, o), {}, 0, dark, o).params.z == -1.0f);
}

TEST_CASE("frame_bytes counts the k-buffer's node pool once, at the size the options give it", "[schedule]") {
  render::options o;
  o.width = 160;
  o.height = 90;
  o.shadow_size = 256;
  const std::size_t pixels = std::size_t(o.width) * std::size_t(o.height);
  const std::size_t pool = std::size_t(dstrans::kbuffer_node_bytes) * std::size_t(render::kbuffer_capacity(o));
  for (render::technique t : {render::technique::interlaced, render::technique::reference}) {
    o.method = t;
    const scene hair = example("hair_panes.json");
    const render::frame_plan p = render::plan_of(hair, o);
    REQUIRE(p.lists);
    render::options tiny = o;
    tiny.kbuffer_nodes = 1;
    const std::size_t full = render::frame_bytes(p, o), small = render::frame_bytes(p, tiny);
    CHECK(full - small == pool - std::size_t(dstrans::kbuffer_node_bytes));
    // What is left is a few targets a pixel and the shadow map, far less than the default pool.
    CHECK(small < pool);
    CHECK(small > pixels * std::size_t(p.pipeline.target("gbuffer.RT0")->bytes_per_pixel));
  }
  // Without lists there is no pool.
  o.method = render::technique::interlaced;
  const scene room = example("glass_room.json");
  const render::frame_plan p = render::plan_of(room, o);
  CHECK(!p.lists);
  render::options tiny = o;
  tiny.kbuffer_nodes = 1;
  CHECK(render::frame_bytes(p, o) == render::frame_bytes(p, tiny));
}

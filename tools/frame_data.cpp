// Implements frame_data.hpp.
#include "frame_data.hpp"

#include <algorithm>
#include <cmath>

#include <dstrans/particles.hpp>

#include "passes.hpp"

namespace dstrans::render {

namespace {
// Cones wider than this are drawn as spheres: a cone's mesh grows without bound towards 90 degrees.
constexpr float widest_cone = 60.0f;

// A sphere around every object of the scene.
struct bounds {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
};
bounds scene_bounds(const scene& s) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const object& ob : s.objects)
    for (const glm::vec3& p : ob.geometry.positions) {
      const glm::vec3 w = glm::vec3(ob.transform * glm::vec4(p, 1.0f));
      lo = glm::min(lo, w);
      hi = glm::max(hi, w);
    }
  if (!(lo.x <= hi.x)) return {};
  return {(lo + hi) * 0.5f, glm::length(hi - lo) * 0.5f};
}

// The near and far planes of a spot light's shadow map: where the scene's bounds begin and end seen from
// the light, within its range. Derived from lengths of the scene alone, so that a scene scaled uniformly
// gets the same window depths (a constant floor on the near plane made shadows depend on the scale).
glm::vec2 shadow_planes(const bounds& b, const light& l) {
  const float d = glm::length(b.centre - l.position);
  const float far_plane = std::min(l.range, d + b.radius);
  return {std::clamp(d - b.radius, far_plane * 1e-3f, far_plane * 0.5f), far_plane};
}

glm::mat4 spot_view(const light& l) {
  const glm::vec3 up = std::fabs(l.direction.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::lookAtRH(l.position, l.position + l.direction, up);
}

// The shape that bounds a light's reach, whatever the camera.
volume shape_of(const light& l) {
  if (l.kind == light_kind::directional) return volume::fullscreen;
  if (l.kind == light_kind::spot && l.outer_angle <= widest_cone) return volume::cone;
  return volume::sphere;
}

}  // namespace

result<bool> fits_device(const options& o, int largest) {
  const int wanted = std::max({o.width, o.height, o.shadow_size});
  if (wanted > largest)
    return failure{"a " + std::to_string(o.width) + "x" + std::to_string(o.height) + " frame with a " +
                   std::to_string(o.shadow_size) + "^2 shadow map needs images " + std::to_string(wanted) +
                   " texels a side; this device's largest is " + std::to_string(largest)};
  return true;
}

volume volume_of(const light& l, const options& o) { return o.fullscreen_lights ? volume::fullscreen : shape_of(l); }

basis particle_basis(const options& o) {
  if (o.particles == options::particle_light::four_axes) return four_axes();
  basis b = six_axes();
  if (o.particles == options::particle_light::fourteen_axes)  // a user-supplied set: the cube's faces and corners
    for (int i = 0; i < 8; ++i) b.axes.push_back(glm::normalize(glm::vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1)));
  return b;
}

volume_atlas particle_atlas(const scene& s, const options& o) {
  std::vector<volume_grid> grids;
  const int n = std::clamp(o.volume_cells, 1, 256);
  for (const particle_system& ps : s.particles) {
    const auto [lo, hi] = particle_bounds(ps);
    grids.push_back(fit_grid(lo, hi, glm::ivec3(n)));
  }
  return pack_volumes(grids, int(particle_basis(o).axes.size()));
}

std::vector<particle_region> particle_regions(const scene& s, const volume_atlas& a) {
  std::vector<particle_region> out;
  for (std::size_t r = 0; r < a.regions.size() && r < s.particles.size(); ++r) {
    const volume_grid& g = a.regions[r];
    out.push_back({glm::vec4(glm::vec3(g.origin), float(s.particles[r].material)), glm::vec4(glm::vec3(g.scale), float(a.slab)),
                   glm::vec4(glm::vec3(a.offsets[r]), 0.0f), glm::vec4(glm::vec3(g.dims), 0.0f)});
  }
  return out;
}

particle_plan particle_plan_of(const scene& s, const frame_plan& p, const options& o) {
  particle_plan out;
  out.on = p.on.has(effect::light_volumes) && !p.forward;
  out.reference = out.on && o.particles == options::particle_light::forward;
  out.baking = out.on && !out.reference;
  out.atlas = particle_atlas(s, o);
  const std::vector<light_block> blocks = light_blocks(s);
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const light_block& b = blocks[i];
    const volume_light v{glm::vec4(glm::vec3(b.position_range), b.direction_kind.w),
                         glm::vec4(glm::vec3(b.direction_kind), b.position_range.w), b.colour_cos_outer,
                         glm::vec4(b.cos_inner.x, float(i), 0.0f, 0.0f)};
    (p.lookups[i] != shadow_mode::off ? out.shadowed_lights : out.unshadowed_lights).push_back(v);
  }
  out.shadows = out.shadowed_lights.empty() ? shadow_mode::off : p.shadows;
  return out;
}

frame_plan plan_of(const scene& s, const options& o) {
  frame_plan p{};
  effects e = effects_of(scene_features(s));
  if (o.refraction <= 0.0f) e = e.without(effect::refraction);
  if (o.shadows != shadow_mode::transparent) e = e.without(effect::transparent_shadows);
  if (o.shadows == shadow_mode::off) e = e.without(effect::shadows);
  e.bits |= o.force.bits;  // forced code runs even where the options leave its effect nothing to do
  p.on = completed(e);
  p.pipeline = o.layout == gbuffer_layout::compact ? plan_pipeline<compact_gbuffer>(p.on) : plan_pipeline<thesis_gbuffer>(p.on);
  p.shadows = !p.on.has(effect::shadows)                ? shadow_mode::off
              : p.on.has(effect::transparent_shadows) ? shadow_mode::transparent
                                                      : shadow_mode::opaque;
  // A light whose cone reaches no glass looks its map up plainly, unless the transparent lookup is forced.
  for (const light& l : s.lights)
    p.lookups.push_back(!casts_shadows(l) || p.shadows == shadow_mode::off ? shadow_mode::off
                        : p.shadows == shadow_mode::transparent &&
                                (sees_transparency(s, l) || o.force.has(effect::transparent_shadows))
                            ? shadow_mode::transparent
                            : shadow_mode::opaque);
  p.forward = is_forward(o.method);
  p.forward_depth = o.method == technique::forward_depth;
  p.peeling = o.method == technique::peeling;
  p.layers = p.forward ? 0 : p.peeling ? 2 : 1;
  // The scene's post-processing chain, on the deferred techniques (it reads the G-buffer): its passes and
  // targets join the plan, each target the final image's format.
  if (!p.forward) {
    p.post = plan_post(s.post, o.method == technique::interlaced && p.on.has(effect::transparency));
    const target_desc t = final_target_desc(o.float_targets);
    for (const post_pass& pass : p.post.passes) {
      std::vector<std::string> reads;
      for (const std::string& in : pass.inputs)
        if (in == "gbuffer")
          for (int k = 0; k < 4; ++k) reads.push_back("gbuffer.RT" + std::to_string(k));
        else reads.push_back(in == "frame" ? "output" : "post." + in);
      p.pipeline.passes.push_back({"post " + pass.name, reads, {"post." + pass.output}, pass.switches});
    }
    for (const std::string& name : p.post.targets) {
      p.pipeline.targets.push_back({"post." + name, info(t.fmt).name, info(t.fmt).bytes_per_pixel, false});
      p.pipeline.bytes_per_pixel += info(t.fmt).bytes_per_pixel;
    }
  }
  return p;
}

frame_schedule schedule_of(const scene& s, const frame_plan& p, const options& o) {
  frame_schedule out;
  auto add = [&](const std::string& timer, const std::string& label, pass_kind kind, int light,
                 std::vector<std::string> reads, std::vector<std::string> writes) {
    out.passes.push_back({timer, label, kind, light, std::move(reads), std::move(writes)});
  };
  const std::string gbuffer[2] = {"gbuffer", "gbuffer 2"}, light_buffer[2] = {"light buffer", "light buffer 2"};
  for (int k = 0; k < p.layers; ++k)
    add("gbuffer", k ? "gbuffer pass, second layer" : "gbuffer pass", pass_kind::geometry, -1,
        k ? std::vector<std::string>{"scene", gbuffer[0]} : std::vector<std::string>{"scene"}, {gbuffer[k]});
  if (p.forward) add("ambient", "forward ambient pass", pass_kind::geometry, -1, {"scene"}, {"lit"});
  const particle_plan smoke = particle_plan_of(s, p, o);
  if (smoke.baking && !smoke.unshadowed_lights.empty())
    add("bake", "bake pass", pass_kind::dispatch, -1, {"scene"}, {"volume texels"});
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    const int l = int(i);
    const std::string n = std::to_string(i);
    const bool shadowed = p.lookups[i] != shadow_mode::off;
    std::vector<std::string> reads{"scene"};
    if (shadowed) {
      add("shadow", "shadow pass, light " + n, pass_kind::geometry, l, {"scene"}, {"shadow map"});
      if (smoke.baking) add("bake", "bake pass, light " + n, pass_kind::dispatch, l, {"shadow map"}, {"volume texels"});
      if (smoke.reference) add("particles", "shadow map into its layer, light " + n, pass_kind::transfer, l, {"shadow map"}, {"shadow layers"});
      reads.push_back("shadow map");
    }
    if (p.forward) {
      add("light", "forward light pass, light " + n, pass_kind::geometry, l, reads, {"lit"});
      continue;
    }
    const pass_kind kind = volume_of(s.lights[i], o) == volume::fullscreen ? pass_kind::fullscreen : pass_kind::light_volume;
    for (int k = 0; k < p.layers; ++k) {
      std::vector<std::string> layer_reads = reads;
      layer_reads[0] = gbuffer[k];
      add("light", "light pass, light " + n + (k ? ", second layer" : ""), kind, l, layer_reads, {light_buffer[k]});
    }
  }
  if (smoke.baking) add("bake", "bake pass, into the atlas", pass_kind::transfer, -1, {"volume texels"}, {"volume atlas"});
  if (p.forward) {
    add("blend", "forward blend pass", pass_kind::fullscreen, -1, {"lit"}, {"frame"});
  } else {
    std::vector<std::string> reads{gbuffer[0]};
    // Light buffers start cleared: a scene without lights composes its ambient term alone.
    if (!s.lights.empty()) reads.push_back(light_buffer[0]);
    if (p.peeling) {
      reads.push_back(gbuffer[1]);
      if (!s.lights.empty()) reads.push_back(light_buffer[1]);
    }
    add("compose", "compose pass", pass_kind::fullscreen, -1, reads, {"frame"});
  }
  if (p.on.has(effect::many_layers) && !p.forward) {
    std::vector<std::string> reads{"scene"};
    if (p.shadows != shadow_mode::off && hair_shadow_light(p) >= 0) reads.push_back("shadow map");
    add("capture", "capture pass", pass_kind::geometry, -1, reads, {"kbuffer"});
    add("resolve", "resolve pass", pass_kind::fullscreen, -1, {"kbuffer", "frame"}, {"frame"});
  }
  if (smoke.on)
    add("particles", "particle pass", pass_kind::geometry, -1,
        {gbuffer[0], smoke.baking ? "volume atlas" : smoke.shadowed_lights.empty() ? "scene" : "shadow layers", "frame"},
        {"frame"});
  for (const post_pass& pass : p.post.passes) {
    std::vector<std::string> reads;
    for (const std::string& in : pass.inputs) reads.push_back(in == "gbuffer" ? gbuffer[0] : in);
    add("post " + pass.effect, "post " + pass.name, pass_kind::fullscreen, -1, reads, {pass.output});
  }
  return out;
}

int hair_shadow_light(const frame_plan& p) {
  for (std::size_t i = p.lookups.size(); i-- > 0;)
    if (p.lookups[i] != shadow_mode::off) return int(i);
  return -1;
}

frame_block camera_frame(const scene& s, const options& o) { return camera_frame(s.view, s.ambient, o); }

frame_block camera_frame(const camera& c, glm::vec3 ambient, const options& o) {
  frame_block f{};
  f.view = c.view();
  f.view_proj = c.projection(float(o.width) / float(o.height)) * f.view;
  f.inv_view_proj = glm::inverse(f.view_proj);
  f.camera_position = glm::vec4(c.position, 1.0f);
  f.ambient = glm::vec4(ambient, 0.0f);
  f.size = {o.width, o.height, o.shadow_size, o.shadow_size};
  f.params = {o.refraction, o.shadow_bias, -1.0f, float(o.kbuffer_k)};
  return f;
}

frame_block light_frame(const scene& s, const light_block& l, const options& o) {
  frame_block f = camera_frame(s, o);
  f.view_proj = l.shadow_view_proj;
  return f;
}

std::vector<material_block> material_blocks(const scene& s) {
  std::vector<material_block> out;
  for (const material& m : s.materials)
    out.push_back({glm::vec4(m.diffuse, m.alpha), glm::vec4(m.spec_intensity, m.spec_power, m.refractive ? 1.0f : 0.0f, m.hair ? 1.0f : 0.0f)});
  return out;
}

std::vector<light_block> light_blocks(const scene& s) {
  std::vector<light_block> out;
  const bounds b = scene_bounds(s);
  for (const light& l : s.lights) {
    const glm::vec2 planes = shadow_planes(b, l);
    light_block lb{};
    const float kind = l.kind == light_kind::directional ? 0.0f : l.kind == light_kind::point ? 1.0f : 2.0f;
    lb.position_range = glm::vec4(l.position, l.range);
    lb.direction_kind = glm::vec4(l.direction, kind);
    lb.colour_cos_outer = glm::vec4(l.colour * l.intensity, std::cos(glm::radians(l.outer_angle)));
    lb.cos_inner = glm::vec4(std::cos(glm::radians(l.inner_angle)), l.shadows && l.kind == light_kind::spot ? 1.0f : 0.0f,
                            planes.x, planes.y);
    // The shadow map covers the outer cone; a 90-degree spot would need a 180-degree frustum, so
    // shadow maps stop at 85 degrees and what lies outside them is lit unshadowed. A 0-degree spot lights
    // only its axis, which a frustum of 1 degree holds (one of 0 degrees has an infinite projection).
    const float half = std::clamp(l.outer_angle, 0.5f, 85.0f);
    if (l.kind == light_kind::spot)
      lb.shadow_view_proj = glm::perspectiveRH_ZO(glm::radians(2.0f * half), 1.0f, planes.x, planes.y) * spot_view(l);
    switch (shape_of(l)) {
      case volume::fullscreen: lb.volume = glm::mat4(1.0f); break;
      case volume::sphere: lb.volume = glm::scale(glm::translate(glm::mat4(1.0f), l.position), glm::vec3(l.range)); break;
      case volume::cone: {
        // The unit cone opens along +Z; a half turn about Y points it down the view space -Z, which the
        // inverse view turns to the light's direction (a rotation: the winding stays outward).
        const float r = l.range * std::tan(glm::radians(l.outer_angle));
        const glm::mat4 turn = glm::inverse(spot_view(l)) * glm::scale(glm::mat4(1.0f), glm::vec3(-1, 1, -1));
        lb.volume = turn * glm::scale(glm::mat4(1.0f), glm::vec3(r, r, l.range));
        break;
      }
    }
    out.push_back(lb);
  }
  return out;
}


}  // namespace dstrans::render

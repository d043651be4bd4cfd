// A frame as the passes it runs, in order: which step of the technique each is, which light it serves, its
// fixed-function state and clears, what the engine draws in it, what it reads and what it writes.
// Per-light passes are entries of the list, and a pass exists only for an effect the frame draws; the
// executors walk the list (a test compares what they ran with it).
//
//   dstrans::frame_schedule s;
//   s.passes.push_back({"gbuffer", "gbuffer pass", dstrans::pass_kind::geometry, -1, {"scene"}, {"gbuffer"}});
//   s.passes.push_back({"compose", "compose pass", dstrans::pass_kind::fullscreen, -1, {"gbuffer"}, {"final"}});
//   auto ok = dstrans::check_schedule(s, {"scene"}, {"final"});   // reads come after writes; nothing is unused
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "../result.hpp"

namespace dstrans {

// What a pass draws: the scene's geometry (or the particles' quads), a light's volume mesh, the full-screen
// triangle, a compute dispatch, or a copy.
enum class pass_kind { geometry, light_volume, fullscreen, dispatch, transfer };

inline const char* pass_kind_name(pass_kind k) {
  switch (k) {
    case pass_kind::geometry: return "geometry";
    case pass_kind::light_volume: return "light volume";
    case pass_kind::fullscreen: return "full screen";
    case pass_kind::dispatch: return "dispatch";
    case pass_kind::transfer: return "transfer";
  }
  return "?";
}

// Which step of the technique a pass is, which decides its program and bindings: the G-buffer, forward
// rendering's ambient pass, a light's shadow map, a light into the light buffer or (forward) into the lit
// colour, the light volumes' bake of the unshadowed lights or of one shadowed light, a shadow map copied
// into its layer, the compose or forward blend, the k-buffer's capture
// and resolve, the particles, a post-processing pass.
enum class pass_step {
  gbuffer, ambient, shadow, light, forward_light, bake, bake_light, shadow_layer, compose, blend, capture,
  resolve, particles, post
};

// A draw's fixed-function state. Blending `add` sums (ONE, ONE); `over` puts a premultiplied colour, whose
// alpha is what it keeps of what lies behind it, over what is there and keeps the target's alpha (colour
// ONE, SRC_ALPHA; alpha ZERO, ONE); `layer` does the same and multiplies the target's alpha by the
// source's, so that a layer cleared to (0, 0, 0, 1) ends holding what it keeps of what lies behind it
// (alpha ZERO, SRC_ALPHA). Culling `front` draws a light volume's back faces.
enum class depth_test { off, less, less_equal };
enum class blending { off, add, over, layer };
enum class culling { off, front };
struct pass_state {
  depth_test depth = depth_test::off;
  bool depth_write = false, depth_clamp = false;
  blending blend = blending::off;
  culling cull = culling::off;
  // The pass keeps only the nearest surface at each pixel (a shadow map), so it may cull the back faces of
  // closed objects wherever that changes no texel but by rounding on a silhouette (culls_back_faces,
  // frame/culling.hpp; index_run::cull_back).
  bool cull_closed = false;
};

// What the engine draws in a geometry pass: every surface but hair, the hair, or both; the particles' quads
// and the lights' meshes are the executor's own. With options::opaque_shadows_depth_only a transparent
// shadow map is drawn in two passes a view: `opaque`, the surfaces of opaque materials (material::opaque),
// by their depth alone, then `not_opaque`, everything else (glass, alpha-tested surfaces, hair). A callback
// that cannot tell them apart may draw nothing for the first and everything for the second.
enum class geometry_set { none, surfaces, hair, everything, opaque, not_opaque };

struct scheduled_pass {
  scheduled_pass() = default;
  scheduled_pass(std::string timer_name, std::string label_text, pass_kind k, int light_index, std::vector<std::string> read,
                 std::vector<std::string> written)
      : timer(std::move(timer_name)), label(std::move(label_text)), kind(k), light(light_index), reads(std::move(read)),
        writes(std::move(written)) {}
  std::string timer;  // what its time is reported as ("gbuffer", "light", ...: a frame's pass_ms)
  std::string label;  // its debug label ("light pass, light 2, second layer")
  pass_kind kind = pass_kind::geometry;
  int light = -1;     // the light it serves; -1: none
  std::vector<std::string> reads, writes;  // resources by name ("gbuffer", "shadow map", "final", ...)
  pass_step step = pass_step::compose;
  int index = 0;      // the G-buffer layer it serves (peeling's second: 1), a post pass's place in the chain,
                      // or the view of a shadow map it draws (light_frame's)
  glm::ivec4 area{0}; // where it draws: x, y (from the top left), width, height; zero size: the whole target
  pass_state state;
  geometry_set draws = geometry_set::none;
  // Before it draws: its colour attachments cleared to these (none: kept), its depth to the far plane.
  std::vector<glm::vec4> clears;
  bool clear_depth = false;
  // The world-to-clip matrix its geometry is drawn with: a shadow pass's light view's, every other pass's
  // the camera's this frame (set_camera_view), so that an engine can cull (frame/culling.hpp). Zero: unknown.
  glm::mat4 view_proj{0.0f};
};

struct frame_schedule {
  std::vector<scheduled_pass> passes;
  std::vector<std::string> cleared;  // resources cleared to zero as the frame begins, outside every pass
};

// Of a flattened scene's `count` indices, hair last from `hair_first` (dstrans::flatten), the run a pass
// that draws `set` draws, not knowing which objects are opaque: none for `opaque`, all for `not_opaque`.
struct index_run {
  std::size_t first = 0, count = 0;
  bool cull_back = false;  // its triangles may be drawn with their back faces culled (visible_runs)
};
inline index_run drawn_indices(geometry_set set, std::size_t hair_first, std::size_t count) {
  if (set == geometry_set::none || set == geometry_set::opaque) return {};
  if (set == geometry_set::surfaces) return {0, hair_first};
  if (set == geometry_set::hair) return {hair_first, count - hair_first};
  return {0, count};
}

// Gives every pass of `s` but the shadow passes the camera's world-to-clip matrix of this frame: what a
// renderer does before it runs them.
inline void set_camera_view(frame_schedule& s, const glm::mat4& view_proj) {
  for (scheduled_pass& pass : s.passes)
    if (pass.step != pass_step::shadow) pass.view_proj = view_proj;
}

// What a frame's passes took on the GPU: the timers in the order they ran (a pass each), each timer's
// sum, and the whole frame from its first pass to its last; from each pass's time in schedule order.
struct frame_times {
  std::vector<std::string> schedule;
  std::map<std::string, double> pass_ms;
  double frame_ms = 0.0;
};
inline frame_times times_of(const frame_schedule& s, const std::vector<double>& pass_ms, double frame_ms) {
  frame_times t;
  for (std::size_t k = 0; k < s.passes.size() && k < pass_ms.size(); ++k) {
    t.schedule.push_back(s.passes[k].timer);
    t.pass_ms[s.passes[k].timer] += pass_ms[k];
  }
  t.frame_ms = frame_ms;
  return t;
}

// Whether every pass reads only what an earlier pass wrote or the frame is given (`inputs`), and everything
// written is read by a later pass or is one of `outputs`; the failure names the first pass that is not so.
inline result<bool> check_schedule(const frame_schedule& s, const std::vector<std::string>& inputs,
                                   const std::vector<std::string>& outputs) {
  auto has = [](const std::vector<std::string>& v, const std::string& x) {
    for (const std::string& e : v)
      if (e == x) return true;
    return false;
  };
  std::vector<std::string> written = inputs;
  for (const scheduled_pass& p : s.passes) {
    for (const std::string& r : p.reads)
      if (!has(written, r)) return failure{p.label + " reads " + r + ", which no pass before it writes"};
    for (const std::string& w : p.writes) written.push_back(w);
  }
  for (std::size_t i = 0; i < s.passes.size(); ++i)
    for (const std::string& w : s.passes[i].writes) {
      bool read = has(outputs, w);
      for (std::size_t j = i + 1; j < s.passes.size() && !read; ++j) read = has(s.passes[j].reads, w);
      if (!read) return failure{s.passes[i].label + " writes " + w + ", which nothing reads"};
    }
  return true;
}

}  // namespace dstrans

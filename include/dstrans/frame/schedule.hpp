// A frame as the passes it runs, in order: what kind each is, which light it serves, what it reads and
// what it writes. Per-light passes are entries of the list, and a pass exists only for an effect the
// frame draws; the renderers run the list (a test compares what they ran with it).
//
//   dstrans::frame_schedule s;
//   s.passes.push_back({"gbuffer", "gbuffer pass", dstrans::pass_kind::geometry, -1, {"scene"}, {"gbuffer"}});
//   s.passes.push_back({"compose", "compose pass", dstrans::pass_kind::fullscreen, -1, {"gbuffer"}, {"final"}});
//   auto ok = dstrans::check_schedule(s, {"scene"}, {"final"});   // reads come after writes; nothing is unused
#pragma once

#include <string>
#include <vector>

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

struct scheduled_pass {
  std::string timer;  // what its time is reported as ("gbuffer", "light", ...: a frame's pass_ms)
  std::string label;  // its debug label ("light pass, light 2, second layer")
  pass_kind kind;
  int light = -1;     // the light it serves; -1: none
  std::vector<std::string> reads, writes;  // resources by name ("gbuffer", "shadow map", "final", ...)
};

struct frame_schedule {
  std::vector<scheduled_pass> passes;
};

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

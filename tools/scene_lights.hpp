// A scene lit by fewer of its lights, as the bench sweeps light counts and tests draw glass_room fast.
//
//   const dstrans::scene two = dstrans::cli::with_spot_lights(room, 2);
#pragma once

#include <dstrans/scene.hpp>

namespace dstrans::cli {

// `s` with only its first `n` spot lights (the thesis lit its scene with spot lights).
inline scene with_spot_lights(const scene& s, int n) {
  scene out = s;
  out.lights.clear();
  for (const light& l : s.lights)
    if (l.kind == light_kind::spot && int(out.lights.size()) < n) out.lights.push_back(l);
  return out;
}

}  // namespace dstrans::cli

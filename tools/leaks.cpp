// Implements leaks.hpp with the shared refraction formulas the forward blend pass uses.
#include "leaks.hpp"

#include <dstrans/interlace.hpp>
#include <dstrans/refraction.hpp>
#include <dstrans/surface.hpp>

#include <dstrans/frame/passes.hpp>

namespace dstrans::render {

leaks count_leaks(const frame& with_depth, const scene& s, const options& o) {
  leaks out;
  out.pixels.assign(std::size_t(o.width) * std::size_t(o.height), false);
  const glm::ivec2 size{o.width, o.height};
  const glm::mat3 view(camera_frame(s, o).view);
  auto at = [&](int target, glm::ivec2 p) {
    return decode(forward_targets(true, o.float_targets)[std::size_t(target)].fmt, with_depth.lit[std::size_t(target)][std::size_t(p.y * size.x + p.x)]);
  };
  for (int y = 0; y < size.y; ++y)
    for (int x = 0; x < size.x; ++x) {
      const glm::ivec2 p{x, y}, q = interlace::rows::partner(p, size);
      const float a = at(0, p).w, b = at(0, q).w;
      if (a >= 1.0f && b >= 1.0f) continue;
      const glm::ivec2 tp = a <= b ? p : q;
      const glm::vec3 n = shader::dst_decode_normal(glm::vec3(at(1, tp)));
      const glm::ivec2 moved = shader::dst_refraction_pixel(p, size, view * n, o.refraction);
      const glm::ivec2 moved_partner = interlace::rows::partner(moved, size);
      const float alpha_moved = at(0, moved).w, alpha_partner = at(0, moved_partner).w;
      const bool by_depth = shader::dst_refraction_source(at(2, tp).x, alpha_moved, at(2, moved).x, alpha_partner,
                                                          at(2, moved_partner).x) != 0;
      const bool by_mask = shader::dst_refraction_accepted_by_mask(alpha_moved, alpha_partner);
      out.foreground_accepted += by_mask && !by_depth;
      out.background_rejected += !by_mask && by_depth;
      out.pixels[std::size_t(y * size.x + x)] = by_mask != by_depth;
    }
  return out;
}

}  // namespace dstrans::render

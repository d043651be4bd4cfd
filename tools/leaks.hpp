// Figure 4.7's two refraction errors of forward rendering without depth, counted on the CPU.
#pragma once

#include <cstddef>
#include <vector>

#include <dstrans/scene.hpp>

#include <dstrans/frame/plan.hpp>
#include "frame_output.hpp"

namespace dstrans::render {

struct leaks {
  std::size_t foreground_accepted = 0, background_rejected = 0;
  std::vector<bool> pixels;  // where either happens
};

// Replays the forward blend pass's choice of the moved sample on the buffers of forward rendering with
// depth (`with_depth.lit`: colour and alpha, normal, depth) and counts the pixels where the glass-coverage
// test (forward without depth) takes a sample that depth rejects (a foreground object leaks in), and
// where it rejects one that depth takes (background beside the glass is lost). The replay rounds the
// offset half to even, as Mesa does; GLSL leaves that direction open.
leaks count_leaks(const frame& with_depth, const scene& s, const options& o);

}  // namespace dstrans::render
